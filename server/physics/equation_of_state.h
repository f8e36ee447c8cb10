// Weakly compressible water: linear equation of state (Eq. 6 with ERRATA.md) and the artificial
// speed of sound (Eq. 24a).
#pragma once

#include <algorithm>
#include <cmath>

#include "server/core/types.h"

namespace cascade {

// The lowest gauge pressure free water takes: at its vapour pressure it cavitates and carries no
// more tension (2.34 kPa absolute at 20 °C, Wagner & Pruss 2002's IAPWS-95 tables; gauge against
// the standard atmosphere, 101.325 kPa, the pore-air pressure p_a = 0 of Section 2.2). Water in SPH
// has no other bound below: a particle torn from its neighbours where a slide entered the channel
// reached −6 MPa (ρ_w = 130 kg/m³) and was pulled through the floor (cases/cascade_storm_2d.yaml,
// measured with an earlier form of the soil-wall contact).
inline constexpr double kCavitationPressure = 2339.0 - 101325.0;  // Pa, gauge

template <typename Real>
struct WaterConstants {
  Real rho0;    // ρ_w0
  Real c0;      // c_w0
  Real delta;   // δ of the δ-SPH density diffusion (Eq. 23a)
  Real alpha;   // α_μ,w of the artificial viscosity (Eq. 23b)

  // Eq. 6: p_w = K_w/ρ_w0 (ρ_w − ρ_w0) with K_w = ρ_w0 c_w0², the bulk modulus that the
  // artificial sound speed stands for, down to the cavitation pressure.
  CASCADE_HD Real pressure(Real water_density) const {
    const Real p = c0 * c0 * (water_density - rho0);
    return p > Real(kCavitationPressure) ? p : Real(kCavitationPressure);
  }
  CASCADE_HD Real density(Real pressure) const { return rho0 + pressure / (c0 * c0); }
};

// Eq. 24a: c_w0 >= 10 max(v_max, sqrt(Δp_max / ρ_w0)); the smallest value it allows.
inline double artificial_sound_speed(double max_speed, double max_pressure, double rho0) {
  return 10.0 * std::max(max_speed, std::sqrt(std::max(max_pressure, 0.0) / rho0));
}

}  // namespace cascade
