// Numerical density (Eq. 22): dρ_i/dt = ρ_i Σ_j V_j (v_i − v_j)·∇_i W_ij, for every phase, with
// no diffusion term (ERRATA.md). It defines the particle volume V_i = m/ρ_i used in every sum.
#pragma once

#include "server/core/types.h"

namespace cascade {

// One neighbour's contribution to Σ_j V_j (v_i − v_j)·∇_i W_ij, the velocity divergence with its
// sign flipped; Eq. 22 multiplies the sum by ρ_i, Eq. 23a by ρ_w,i.
template <typename Real, int Dim>
CASCADE_HD inline Real velocity_divergence_pair(Real volume_j, const Vec<Real, Dim>& v_ij, const Vec<Real, Dim>& grad_w) {
  return volume_j * v_ij.dot(grad_w);
}

// The same with ∇_i W_ij = F x_ij written out: V_j F (v_ij·x_ij), for the neighbour loops that sum
// scalars (docs/performance.md, "The neighbour loops").
template <typename Real>
CASCADE_HD inline Real velocity_divergence_pair(Real volume_j, Real gradient_factor, Real v_ij_dot_x_ij) {
  return volume_j * gradient_factor * v_ij_dot_x_ij;
}

}  // namespace cascade
