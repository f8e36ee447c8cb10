// δ-SPH density diffusion of the water continuity equation (Eqs. 23a, 24b; Marrone et al. 2011).
#pragma once

#include "server/core/types.h"

namespace cascade {

// One neighbour's V_j ψ_ij·∇_i W_ij with
//   ψ_ij = 2 (ρ_w,i − ρ_w,j) x_ij / (|x_ij|² + η²) − (⟨∇ρ_w⟩_i^L + ⟨∇ρ_w⟩_j^L).
// With ∇_i W_ij = F(r) x_ij and F < 0 the first part is −2|F|(ρ_w,i − ρ_w,j): it diffuses.
// For a linear density field the two parts cancel pair by pair, so hydrostatic water keeps its
// density gradient. Eq. 23a multiplies the sum by δ h c_w0.
// Takes 1/(|x_ij|² + η²), which μ_ij of Eq. 24c shares.
// Written with ∇_i W_ij = F x_ij, so that V_j ψ_ij·∇_i W_ij = V_j F ψ_ij·x_ij with
//   ψ_ij·x_ij = 2 (ρ_w,i − ρ_w,j) |x_ij|² / (|x_ij|² + η²) − (⟨∇ρ_w⟩_i^L + ⟨∇ρ_w⟩_j^L)·x_ij;
// gradient_sum_along is the last dot product, F the kernel's gradient_factor.
template <typename Real>
CASCADE_HD inline Real density_diffusion_pair(Real volume_j, Real gradient_factor, Real rho_w_i, Real rho_w_j, Real r2,
                                              Real inv_r2_eta2, Real gradient_sum_along) {
  return volume_j * gradient_factor * (Real(2) * (rho_w_i - rho_w_j) * r2 * inv_r2_eta2 - gradient_sum_along);
}

}  // namespace cascade
