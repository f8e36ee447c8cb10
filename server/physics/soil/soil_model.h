// The soil constitutive model of a material: its parameters, one device-callable stress update
// that dispatches on the model kind, and the host-side parameter check.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "server/core/types.h"
#include "server/physics/soil/drucker_prager.h"
#include "server/physics/soil/jaumann_rate.h"
#include "server/physics/soil/linear_elastic.h"

namespace cascade {

// Parameters in SI units; angles in radians (case files give degrees, as the paper's tables do,
// and the scenario loader converts them). The names are those validate() reports.
template <typename Real>
struct SoilModel {
  enum class Kind : std::uint8_t { linear_elastic, drucker_prager };

  Kind kind = Kind::linear_elastic;
  Real youngs_modulus = 0;            // E [Pa]
  Real poisson_ratio = 0;             // ν [-]
  Real peak_cohesion = 0;             // c'_p [Pa] (Eq. 12a)
  Real residual_cohesion = 0;         // c'_r [Pa]
  Real peak_friction_angle = 0;       // φ'_p [rad] (Eq. 12b)
  Real residual_friction_angle = 0;   // φ'_r [rad]
  Real dilatancy_angle = 0;           // ψ [rad] (Eq. 10b; the paper's tables give none: 0)
  Real softening_coefficient = 0;     // η [-] (Eq. 12)
  Real suction_cohesion = 0;          // c_sp = the tables' c_s0 [Pa] (Eq. 13a)
  Real suction_cohesion_rate = 0;     // B_s [-] (Eq. 13a)
  Real suction_friction_rate = 0;     // A_s [rad] (Eq. 13b)
  Real atmospheric_pressure = Real(101e3);  // p_atm [Pa] (Eq. 13)

  CASCADE_HD LinearElastic<Real> elastic() const {
    return LinearElastic<Real>::from_young_poisson(youngs_modulus, poisson_ratio);
  }

  CASCADE_HD DruckerPrager<Real> drucker_prager() const {
    return {elastic(),
            peak_cohesion,
            residual_cohesion,
            peak_friction_angle,
            residual_friction_angle,
            dilatancy_angle,
            softening_coefficient,
            suction_cohesion,
            suction_cohesion_rate,
            suction_friction_rate,
            atmospheric_pressure};
  }

  // One particle, one step: the stress σ' and κ at the start of the step, the strain and spin
  // increments ε̇Δt and ω̇Δt (Eqs. 26c, 26d, as full 3D tensors, see velocity_gradient_3d) and the
  // suction p_c = −p_w [Pa]. The Jaumann rotation (Eq. 8) is included. A linear-elastic soil
  // never yields and keeps its κ.
  CASCADE_HD StressUpdate<Real> update(const Mat<Real, 3>& stress, const Mat<Real, 3>& strain_increment,
                                       const Mat<Real, 3>& spin_increment, Real suction, Real kappa) const {
    if (kind == Kind::drucker_prager)
      return drucker_prager().update(stress, strain_increment, spin_increment, suction, kappa);
    return {elastic().update(stress, strain_increment, spin_increment), kappa, PlasticRegime::elastic};
  }

  // yield_ratio (drucker_prager.h) at suction p_c [Pa] and κ; 0 for a linear-elastic soil, which
  // never yields.
  CASCADE_HD Real yield_ratio(const Mat<Real, 3>& stress, Real suction, Real kappa) const {
    if (kind != Kind::drucker_prager) return Real(0);
    return cascade::yield_ratio(stress, drucker_prager().strength(kappa, suction));
  }

  // Host only. Empty when the parameters are usable, else one message that names the first bad
  // parameter. The strength parameters are checked only for kind drucker_prager.
  std::string validate() const {
    constexpr double kRightAngle = 1.57079632679489661923;
    constexpr double kDegree = 180.0 / 3.14159265358979323846;
    const auto number = [](double v) { return std::to_string(v); };
    const auto angle = [&](double v) { return number(v * kDegree) + "° (" + number(v) + " rad)"; };
    // Written as !(good) so that NaN fails every check.
    if (kind != Kind::linear_elastic && kind != Kind::drucker_prager) return "kind: not a known soil model";
    if (!(youngs_modulus > 0) || !std::isfinite(double(youngs_modulus)))
      return "youngs_modulus must be a finite value > 0 Pa, got " + number(youngs_modulus);
    if (!(poisson_ratio > -1 && poisson_ratio < 0.5))
      return "poisson_ratio must lie in (-1, 0.5), got " + number(poisson_ratio);
    if (kind == Kind::linear_elastic) return "";
    if (!(peak_cohesion >= 0) || !std::isfinite(double(peak_cohesion)))
      return "peak_cohesion must be a finite value >= 0 Pa, got " + number(peak_cohesion);
    if (!(residual_cohesion >= 0))
      return "residual_cohesion must be >= 0 Pa, got " + number(residual_cohesion);
    if (!(residual_cohesion <= peak_cohesion))
      return "residual_cohesion must not exceed peak_cohesion (" + number(peak_cohesion) + " Pa), got " +
             number(residual_cohesion);
    if (!(peak_friction_angle >= 0 && peak_friction_angle < kRightAngle))
      return "peak_friction_angle must lie in [0°, 90°), got " + angle(peak_friction_angle);
    if (!(residual_friction_angle >= 0))
      return "residual_friction_angle must be >= 0°, got " + angle(residual_friction_angle);
    if (!(residual_friction_angle <= peak_friction_angle))
      return "residual_friction_angle must not exceed peak_friction_angle (" + angle(peak_friction_angle) +
             "), got " + angle(residual_friction_angle);
    if (!(dilatancy_angle >= 0))
      return "dilatancy_angle must be >= 0° (plastic compaction is not modelled), got " + angle(dilatancy_angle);
    if (!(dilatancy_angle <= peak_friction_angle))
      return "dilatancy_angle must not exceed peak_friction_angle (" + angle(peak_friction_angle) + "), got " +
             angle(dilatancy_angle);
    if (!(softening_coefficient >= 0) || !std::isfinite(double(softening_coefficient)))
      return "softening_coefficient must be a finite value >= 0, got " + number(softening_coefficient);
    if (!(suction_cohesion >= 0) || !std::isfinite(double(suction_cohesion)))
      return "suction_cohesion must be a finite value >= 0 Pa, got " + number(suction_cohesion);
    if (!(suction_cohesion_rate >= 0) || !std::isfinite(double(suction_cohesion_rate)))
      return "suction_cohesion_rate must be a finite value >= 0, got " + number(suction_cohesion_rate);
    if (!(suction_friction_rate >= 0) || !std::isfinite(double(suction_friction_rate)))
      return "suction_friction_rate must be a finite value >= 0 rad, got " + number(suction_friction_rate);
    if (!(atmospheric_pressure > 0) || !std::isfinite(double(atmospheric_pressure)))
      return "atmospheric_pressure must be a finite value > 0 Pa, got " + number(atmospheric_pressure);
    return "";
  }
};

}  // namespace cascade
