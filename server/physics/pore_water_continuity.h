// Pore-water continuity of a soil particle (Eq. 27a with ERRATA.md) and its seepage time-step
// limit (Eqs. 40c, 41):
//   dρ_w,i/dt = −(1/C_r,i) [ ρ_w,i ( ⟨∇·q_w⟩_i + S_max S_e,i ε̇_v,i )
//                            − δ h c_pw0 Σ_{j soil} V_j ψ_ij·∇_i W_ij ],
//   C_r = φ (S_w − K_w ∂S_w/∂p_c) (Eq. 28b), ψ_ij of Eq. 24b on the pore-water densities.
// S_max S_e is the printed S_w less the residual water held by the grains, which the skeleton's
// volume change does not squeeze (grain_bound_water.h); the two agree in a saturated soil.
// The δ-term carries the opposite sign to the printed Eq. 27a, whose form inside −1/C_r [...]
// would be anti-diffusive (ERRATA.md): with it, a local pore-pressure bump decays. ⟨∇·q_w⟩_i is
// the sum of pairwise Darcy exchanges with the soil and a drained wall's dummies, with the rain of
// Eq. 39 as a source at the surface (seepage_exchange.h); free water does not exchange mass with
// the pore water (ERRATA.md).
//   Δt_sp = (γ_w/K_w) h² C_r / (2 K) (Eq. 40c with c_v = C_r, Eq. 41), γ_w = ρ_w0 g.
#pragma once

#include "server/core/types.h"

namespace cascade {

// dρ_w/dt from the two neighbour sums and ε̇_v (Eq. 27a as above).
template <typename Real>
CASCADE_HD inline Real pore_water_density_rate(Real rho_w, Real capacity, Real seepage_divergence, Real skeleton_share,
                                               Real volumetric_strain_rate, Real delta_h_c, Real diffusion) {
  return -(rho_w * (seepage_divergence + skeleton_share * volumetric_strain_rate) - delta_h_c * diffusion) / capacity;
}

// Eq. 40c; +∞ for a dry particle (K = 0).
template <typename Real>
CASCADE_HD inline Real seepage_time_step(Real unit_weight, Real bulk_modulus, Real h, Real capacity, Real conductivity) {
  return unit_weight / bulk_modulus * h * h * capacity / (Real(2) * conductivity);
}

}  // namespace cascade
