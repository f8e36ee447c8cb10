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

  // C_r = φ (S_w − K_w ∂S_w/∂p_c) (Eqs. 28b and 41, ERRATA.md row "Eq. 28b / 41"), the storage
  // factor of the pore-water continuity (Eqs. 3a, 27a) and c_v of the seepage time step
  // (Eq. 40c). K_w is the water bulk modulus (Section 2.2, Table 1: 2×10⁶ Pa; pass the value the
  // pore-water equation of state uses). It follows from ∂(φ S_w ρ_w)/∂t with ∂p_w = (K_w/ρ_w) ∂ρ_w
  // and ∂S_w/∂p_w = −∂S_w/∂p_c: since ∂S_w/∂p_c <= 0, C_r >= φ S_w, the drying soil stores more
  // water per unit density change than the saturated one.
  CASCADE_HD Real capacity(Real p_c, Real porosity, Real water_bulk_modulus) const {
    return porosity * (saturation(p_c) - water_bulk_modulus * saturation_derivative(p_c));
  }

 private:
  // Reached only with a kind outside the enumeration (an unvalidated model): NaN makes the step's
  // non-finite check stop the run instead of silently using some other model.
  CASCADE_HD static Real invalid() { return Real(NAN); }
};

}  // namespace cascade
