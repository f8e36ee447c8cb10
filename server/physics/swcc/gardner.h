// Gardner's exponential soil-water characteristic and hydraulic conductivity curves (paper
// Eq. 42, Section 4.1), whose linearised Richards equation has closed-form transient solutions
// (ERRATA.md, row "Section 4.1").
#pragma once

#include <cmath>

#include "server/core/types.h"

namespace cascade {

// Eq. 42 with its constants as parameters: the paper's column has S_min = 0.23, S_max = 1 and
// α = 2 m⁻¹, with the suction head p_c/(ρ_w0 g). One α serves both curves, as in Eq. 42 and as
// the closed-form solutions require.
template <typename Real>
struct Gardner {
  Real s_min;        // residual degree of saturation (-)
  Real s_max;        // maximum degree of saturation (-)
  Real alpha;        // α, inverse length of the exponential decay (1/m)
  Real unit_weight;  // γ_w = ρ_w0 g, converts p_c to the head p_c/γ_w (Pa/m)

  CASCADE_HD Real saturation_min() const { return s_min; }
  CASCADE_HD Real saturation_max() const { return s_max; }

  // S_w = S_min + (S_max − S_min) exp(−α p_c/γ_w) (Eq. 42a), S_w = S_max for p_c <= 0: the
  // exponential itself would exceed S_max under positive pore pressure.
  CASCADE_HD Real saturation(Real p_c) const { return s_min + (s_max - s_min) * decay(p_c); }

  // dS_w/dp_c = −(S_max − S_min) (α/γ_w) exp(−α p_c/γ_w) for p_c > 0 and 0 for p_c <= 0. The
  // model has a kink at p_c = 0 (its right-hand slope is −(S_max − S_min) α/γ_w); p_c = 0 takes
  // the saturated side, as every model here does.
  CASCADE_HD Real saturation_derivative(Real p_c) const {
    if (p_c <= Real(0)) return Real(0);
    return -(s_max - s_min) * alpha / unit_weight * decay(p_c);
  }

  // K_rel = K/K_sat = exp(−α p_c/γ_w) (Eq. 42b), 1 for p_c <= 0.
  CASCADE_HD Real relative_conductivity(Real p_c) const { return decay(p_c); }

  // exp(−α p_c/γ_w) on the unsaturated side, 1 on the saturated one; exp(−inf) = 0 for huge p_c.
  CASCADE_HD Real decay(Real p_c) const {
    if (p_c <= Real(0)) return Real(1);
    return std::exp(-alpha * p_c / unit_weight);
  }
};

}  // namespace cascade
