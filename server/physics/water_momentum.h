// Water momentum (Eq. 23b with ERRATA.md) and Monaghan's artificial viscosity (Eq. 24c).
#pragma once

#include "server/core/types.h"

namespace cascade {

// One neighbour's −V_j (p_i + p_j) ∇_i W_ij, written as the coefficient −V_j (p_i + p_j) of
// ∇_i W_ij for the neighbour loops that sum scalars. It is divided by ρ_i, the numerical density
// that defines V_i = m/ρ_i, so that the pair force −V_i V_j (p_i + p_j) ∇_i W_ij acting on i is
// exactly the opposite of the one acting on j and Σ m v is conserved to round-off
// (docs/physics.md, "Water momentum").
template <typename Real>
CASCADE_HD inline Real pressure_force_coefficient(Real volume_j, Real p_i, Real p_j) {
  return -volume_j * (p_i + p_j);
}

// The pressure of a pair across the soil-water interface, p_w + S_w p_w,s (free water and the
// skeleton's pore water, docs/physics.md "Soil-water interface"), held at zero or above: the
// contact carries compression only. Under tension air enters between grains and free water
// (the interface meets the free surface wherever a slide enters water) and the two part; SPH would
// otherwise pull them together with the tension of its own separating pairs (the tensile
// instability), and a sliding dry mass dragged water particles into the air at tens of m/s.
// The water's pair with a dummy particle, p_w + p_b, is held the same way (water_interaction.h):
// a solid wall pushes the water and never pulls it into itself (docs/physics.md, "Solid
// boundary").
template <typename Real>
CASCADE_HD inline Real interface_contact_pressure(Real pair_pressure) {
  return pair_pressure > Real(0) ? pair_pressure : Real(0);
}

// The pressure a soil particle shows the free water across the interface. Saturated pores (p_w >= 0)
// are continuous with the free water: they show their pore water's pressure S_w p_w (Bishop's pore
// stress of Eq. 7; the paper's pressure continuity at the interface, Section 3.3). Unsaturated pores
// (p_w < 0) hold air between the free water and their pore water: the mixture's surface then meets
// the water as a solid, and its total traction balances the water's pressure (the skeleton carries
// the difference as effective stress). It shows the water its own pressure carried hydrostatically
// to the soil particle, p + ρ_w0 g·(x_s − x), as a wall's dummy does (docs/physics.md, "Solid
// boundary"), or S_w p_w where that is higher. Before, the suction of unsaturated soil made it a void
// to the water: at a lake's shore the water pressed into the slope and circulated there
// (cases/lake_margin_2d.yaml). Both sides of a pair use it (water_interaction.h, soil_interaction.h),
// so the pair forces stay equal and opposite. Saturated pores keep S_w p_w rather than the larger
// of the two: there both are the same pressure up to the particles' noise, and the larger of them
// biased the interface upwards (the submerged layer's buoyant weight 3.3% off at h/dp 1.5, 1.7%
// with S_w p_w).
// gravity_along is g·(x_s − x), the soil particle's position relative to the water's along gravity.
template <typename Real>
CASCADE_HD inline Real soil_shown_pressure(Real saturation, Real pore_pressure, Real water_pressure, Real water_rho0,
                                           Real gravity_along) {
  const Real pore_stress = saturation * pore_pressure;
  const Real carried = water_pressure + water_rho0 * gravity_along;
  return pore_pressure >= Real(0) || pore_stress > carried ? pore_stress : carried;
}
template <typename Real, int Dim>
CASCADE_HD inline Real soil_shown_pressure(Real saturation, Real pore_pressure, Real water_pressure, Real water_rho0,
                                           const Vec<Real, Dim>& gravity, const Vec<Real, Dim>& soil_minus_water) {
  return soil_shown_pressure(saturation, pore_pressure, water_pressure, water_rho0, gravity.dot(soil_minus_water));
}

// μ_ij = h v_ij·x_ij / (|x_ij|² + η²) (Eq. 24c); also the pair term of the CFL limit (Eq. 40b).
// Takes 1/(|x_ij|² + η²), which the δ-term of Eq. 24b shares.
template <typename Real>
CASCADE_HD inline Real viscosity_mu(Real h, Real v_ij_dot_x_ij, Real inv_r2_eta2) {
  return h * v_ij_dot_x_ij * inv_r2_eta2;
}
template <typename Real, int Dim>
CASCADE_HD inline Real viscosity_mu(Real h, const Vec<Real, Dim>& v_ij, const Vec<Real, Dim>& x_ij, Real inv_r2_eta2) {
  return viscosity_mu(h, v_ij.dot(x_ij), inv_r2_eta2);
}

// α c_0 (m_j / ρ̄_ij) μ_ij ∇_i W_ij for approaching pairs (μ_ij < 0), else 0 (Eqs. 23b, 24c),
// with ρ̄_ij = (ρ_i + ρ_j)/2. h appears once, inside μ_ij: the acceleration then has units m/s².
// Repulsive: μ < 0 and ∇_i W_ij = F x_ij with F < 0 push i away from j.
template <typename Real>
CASCADE_HD inline Real artificial_viscosity_coefficient(Real alpha_c0, Real mass_j, Real rho_i, Real rho_j, Real mu) {
  const Real approaching_mu = mu < Real(0) ? mu : Real(0);
  return Real(2) * alpha_c0 * mass_j / (rho_i + rho_j) * approaching_mu;
}
template <typename Real, int Dim>
CASCADE_HD inline Vec<Real, Dim> artificial_viscosity_pair(Real alpha_c0, Real mass_j, Real rho_i, Real rho_j, Real mu,
                                                          const Vec<Real, Dim>& grad_w) {
  return artificial_viscosity_coefficient(alpha_c0, mass_j, rho_i, rho_j, mu) * grad_w;
}

}  // namespace cascade
