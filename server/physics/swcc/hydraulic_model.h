// One soil's hydraulic model, chosen per material at run time: a tag and the parameters of every
// model (van Genuchten–Mualem, Eqs. 14–15; Gardner, Eq. 42; Liakopoulos fit, Eq. 43), dispatched
// by a switch so that kernels can take it by value (no virtual functions on the device).
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/types.h"
#include "server/physics/swcc/gardner.h"
#include "server/physics/swcc/liakopoulos.h"
#include "server/physics/swcc/van_genuchten.h"

namespace cascade {

// Every function takes the capillary pressure p_c = −p_w (Pa; ERRATA.md, row "Eq. 28b / 41": the
// pore air pressure is zero). p_c <= 0 is the saturated branch: S_w = S_max, K_rel = 1,
// dS_w/dp_c = 0. check_hydraulic_model (hydraulic_model_check.h) validates the parameters.
template <typename Real>
struct HydraulicModel {
  enum class Kind : std::uint8_t { van_genuchten, gardner, liakopoulos };

  Kind kind;
  VanGenuchten<Real> van_genuchten;  // used when kind == Kind::van_genuchten
  Gardner<Real> gardner;             // used when kind == Kind::gardner
  Liakopoulos<Real> liakopoulos;     // used when kind == Kind::liakopoulos

  HydraulicModel() = default;
  CASCADE_HD explicit HydraulicModel(const VanGenuchten<Real>& m)
      : kind(Kind::van_genuchten), van_genuchten(m), gardner{}, liakopoulos{} {}
  CASCADE_HD explicit HydraulicModel(const Gardner<Real>& m)
      : kind(Kind::gardner), van_genuchten{}, gardner(m), liakopoulos{} {}
  CASCADE_HD explicit HydraulicModel(const Liakopoulos<Real>& m)
      : kind(Kind::liakopoulos), van_genuchten{}, gardner{}, liakopoulos(m) {}

  // S_w(p_c) in [saturation_min(), saturation_max()].
  CASCADE_HD Real saturation(Real p_c) const {
    switch (kind) {
      case Kind::van_genuchten: return van_genuchten.saturation(p_c);
      case Kind::gardner: return gardner.saturation(p_c);
      case Kind::liakopoulos: return liakopoulos.saturation(p_c);
    }
    return invalid();
  }

  // dS_w/dp_c <= 0, analytic.
  CASCADE_HD Real saturation_derivative(Real p_c) const {
    switch (kind) {
      case Kind::van_genuchten: return van_genuchten.saturation_derivative(p_c);
      case Kind::gardner: return gardner.saturation_derivative(p_c);
      case Kind::liakopoulos: return liakopoulos.saturation_derivative(p_c);
    }
    return invalid();
  }

  // K_rel = K/K_sat in [0, 1].
  CASCADE_HD Real relative_conductivity(Real p_c) const {
    switch (kind) {
      case Kind::van_genuchten: return van_genuchten.relative_conductivity(p_c);
      case Kind::gardner: return gardner.relative_conductivity(p_c);
      case Kind::liakopoulos: return liakopoulos.relative_conductivity(p_c);
    }
    return invalid();
  }

  // The saturation of the dry limit (p_c → ∞) and of the saturated branch.
  CASCADE_HD Real saturation_min() const {
    switch (kind) {
      case Kind::van_genuchten: return van_genuchten.saturation_min();
      case Kind::gardner: return gardner.saturation_min();
      case Kind::liakopoulos: return liakopoulos.saturation_min();
    }
    return invalid();
  }
  CASCADE_HD Real saturation_max() const {
    switch (kind) {
      case Kind::van_genuchten: return van_genuchten.saturation_max();
      case Kind::gardner: return gardner.saturation_max();
      case Kind::liakopoulos: return liakopoulos.saturation_max();
    }
    return invalid();
  }

  // The residual water held at the grain contacts (pendular and adsorbed water) at the curve's
  // reference porosity: S_min of Eqs. 14 and 42. The Liakopoulos fit (Eq. 43) has no residual
  // water (its S_min is the end of the fit's range), so 0. grain_bound_water.h scales it with the
  // porosity.
  CASCADE_HD Real bound_saturation() const {
    switch (kind) {
      case Kind::van_genuchten: return van_genuchten.saturation_min();
      case Kind::gardner: return gardner.saturation_min();
      case Kind::liakopoulos: return Real(0);
    }
    return invalid();
  }

  // S_e = (S_w − S_b)/(S_max − S_b) in [0, 1] with S_b = bound_saturation(), from each model's
  // own expression, so that it keeps its relative accuracy where S_w is within rounding of S_b.
  CASCADE_HD Real effective_saturation(Real p_c) const {
    switch (kind) {
      case Kind::van_genuchten: return van_genuchten.effective_saturation(p_c);
      case Kind::gardner: return gardner.decay(p_c);
      case Kind::liakopoulos: return liakopoulos.saturation(p_c);
    }
    return invalid();
  }

 private:
  // Reached only with a kind outside the enumeration (an unvalidated model): NaN makes the step's
  // non-finite check stop the run instead of silently using some other model.
  CASCADE_HD static Real invalid() { return Real(NAN); }
};

}  // namespace cascade
