// The divergence of the seepage discharge in the pore-water continuity (Eq. 27a), as Darcy
// exchanges between pairs of particles. Eq. 27b is q_w = −(K/g) ∇Φ with the potential
//   ∇Φ = ∇p_w/ρ_w − (g − a_s),
// and ∇·q_w is taken with the pairwise SPH Laplacian of Brookshaw (1985) and Cleary & Monaghan
// (1999), the arithmetic mean of the conductivities as in the implicit stage (pore_water_network.h):
//   ⟨∇·q_w⟩_i = −s Σ_j V_j ((K_i + K_j)/g) (Φ_i − Φ_j) x_ij·∇_i W_ij / (|x_ij|² + η²),
//   Φ_i − Φ_j = (p_w,i − p_w,j)/ρ̄_w − (g − ā_s)·x_ij,  ρ̄_w, ā_s the means of the pair,
// s the lattice scale that makes the sum exact on the lattice (kernel.h). The pair fluxes are
// antisymmetric, so the pore water is conserved to round-off, and the operator is dissipative for
// every mode, the odd-even one included: the divergence of the renormalised gradient of Eq. 25
// that it replaces is blind to that mode, which grew below a rained surface from round-off
// (docs/physics.md, "Smoothness of the pore pressure"). A hydrostatic pore pressure has Φ_i = Φ_j
// and no flux, also where the support is cut.
//
// Neighbours: soil particles, and the dummies of a drained wall with the pore pressure of Eq. 36
// (the prescribed value mirrored about the ghost node, so that a potential linear across the wall
// has its exact flux) and the conductivity K_i; an impermeable wall's dummies and free water take
// no part (no flux, Eq. 35b; no mass exchange between free and pore water, ERRATA.md). A cut
// support is a face without flux: where a free surface takes the flux condition of Eq. 39, the
// rows under it share its outflow with an O(dp) error in the head, together exactly. Where the
// surface holds a prescribed pressure (ponded, drying, held), water crosses it, and the pairs that
// the cut support lacks are added with the particle's own potential gradient, ∇Φ_i = −g q_w,i/K_i
// (Eq. 27b), on the first moment they leave:
//   Σ_j w_ij (Φ_i − Φ_j) − ∇Φ_i·Σ_j w_ij x_ij,  w_ij the pair's weight,
// at every particle with such a neighbour, so that a linear potential has no divergence there
// (the steady flow of a drained column is then exact). In that moment free water and the dummies of
// every wall count as present sides without flux, so the correction crosses the free surface only.
//
// The flux condition of Eq. 39 enters as a source: each soil particle under it that tops its
// vertical column of the lattice (no particle above it within dp/2 of its axis) takes the
// intensity i over the column's area dp^(d−1), as the implicit stage's network does:
//   ⟨∇·q_w⟩_i −= i dp^(d−1) / V_i.
// The rain volume that reaches the soil is i times its horizontal area, whatever the slope.
#pragma once

#include "server/core/types.h"

namespace cascade {

// Φ_i − Φ_j of the header, per unit (K_i + K_j)/g: the potential difference along the pair.
template <typename Real, int Dim>
CASCADE_HD inline Real seepage_potential_difference(Real p_w_i, Real p_w_j, Real mean_water_density,
                                                    const Vec<Real, Dim>& driving_acceleration,
                                                    const Vec<Real, Dim>& x_ij) {
  return (p_w_i - p_w_j) / mean_water_density - driving_acceleration.dot(x_ij);
}

// One pair's term of Σ_j in ⟨∇·q_w⟩_i (without −s): V_j ((K_i + K_j)/g) (Φ_i − Φ_j) x_ij·∇W/(r² + η²).
template <typename Real, int Dim>
CASCADE_HD inline Real seepage_exchange_pair(Real volume_j, Real pair_conductivity_over_g, Real potential_difference,
                                             const Vec<Real, Dim>& x_ij, Real inv_r2_eta2,
                                             const Vec<Real, Dim>& grad_w) {
  return volume_j * pair_conductivity_over_g * potential_difference * x_ij.dot(grad_w) * inv_r2_eta2;
}

// Whether a neighbour at x_ij = x_i − x_j covers particle i from the rain: above it, within dp/2
// of its vertical axis (the last axis) along every horizontal one.
template <typename Real, int Dim>
CASCADE_HD inline bool covers_from_rain(const Vec<Real, Dim>& x_ij, Real dp) {
  if (!(x_ij[Dim - 1] < Real(0))) return false;
  for (int a = 0; a + 1 < Dim; ++a)
    if (!(x_ij[a] < Real(0.5) * dp && x_ij[a] > Real(-0.5) * dp)) return false;
  return true;
}

}  // namespace cascade
