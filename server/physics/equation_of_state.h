// Weakly compressible water: linear equation of state (Eq. 6 with ERRATA.md) and the artificial
// speed of sound (Eq. 24a).
#pragma once

#include <algorithm>
#include <cmath>

#include "server/core/types.h"

namespace cascade {

template <typename Real>
struct WaterConstants {
  Real rho0;    // ρ_w0
  Real c0;      // c_w0
  Real delta;   // δ of the δ-SPH density diffusion (Eq. 23a)
  Real alpha;   // α_μ,w of the artificial viscosity (Eq. 23b)

  // Eq. 6: p_w = K_w/ρ_w0 (ρ_w − ρ_w0) with K_w = ρ_w0 c_w0², the bulk modulus that the
  // artificial sound speed stands for.
  CASCADE_HD Real pressure(Real water_density) const { return c0 * c0 * (water_density - rho0); }
  CASCADE_HD Real density(Real pressure) const { return rho0 + pressure / (c0 * c0); }
};

// Eq. 24a: c_w0 >= 10 max(v_max, sqrt(Δp_max / ρ_w0)); the smallest value it allows.
inline double artificial_sound_speed(double max_speed, double max_pressure, double rho0) {
  return 10.0 * std::max(max_speed, std::sqrt(std::max(max_pressure, 0.0) / rho0));
}

}  // namespace cascade
