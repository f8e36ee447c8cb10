// The retention curve of a deforming soil: the residual water of a curve is held at the grain
// contacts, so its volume goes with the grains, not with the pores.
//
// A retention curve is measured at one porosity φ0 (the case's `porosity`). Its residual
// saturation S_b0 (bound_saturation(), S_min of Eqs. 14 and 42) is the pendular and adsorbed water
// at the grain contacts, whose volume per unit volume of grains, the residual water ratio
// e_wr = S_b0 e0 (e = φ/(1 − φ)), does not change as the skeleton deforms: at high suction the
// water ratio e_w = S_w e of a soil depends on the suction alone (Romero & Vaunat 2000,
// "Retention curves of deformable clays"; Tarantino 2009, Géotechnique 59(9):751–762). So
//   S_b(φ) = e_wr/e = S_b0 (1 − φ) φ0 / (φ (1 − φ0)),
//   S_w(p_c, φ) = S_b(φ) + (S_max − S_b(φ)) S_e(p_c),
// with S_e(p_c) the curve's effective saturation. S_b is capped at S_max (pores filled with bound
// water, a porosity far below any case's). In the water mass balance per unit volume of grains,
// d(ρ_w S_w e)/dt = −(1 + e) ∇·(ρ_w q_w) with de/dt = (1 + e) ε̇_v, the deformation enters through
//   S_w + e ∂S_w/∂e = S_w − (1 − S_e) S_b = S_max S_e
// (skeleton_water_share): the skeleton's volume change squeezes or sucks only the free water. In a
// saturated soil that is S_max = S_w, Eq. 27a as printed; at residual saturation it vanishes, where
// Eq. 27a's S_w ε̇_v over its storage C_r ≈ φ S_w made the residual water as stiff as the water of a
// saturated soil, dp_w = −(K_w/φ) dε_v, and a dilating dry soil ran to megapascals of suction
// (docs/physics.md, "Grain-bound water").
#pragma once

#include "server/core/types.h"
#include "server/physics/swcc/hydraulic_model.h"

namespace cascade {

// S_b(φ) = S_b0 (1 − φ) φ0 / (φ (1 − φ0)), at most S_max.
template <typename Real>
CASCADE_HD inline Real grain_bound_saturation(const HydraulicModel<Real>& curve, Real reference_porosity,
                                              Real porosity) {
  const Real bound = curve.bound_saturation() * (Real(1) - porosity) * reference_porosity /
                     (porosity * (Real(1) - reference_porosity));
  return bound < curve.saturation_max() ? bound : curve.saturation_max();
}

// S_w(p_c, φ) = S_b(φ) + (S_max − S_b(φ)) S_e(p_c); the curve's own S_w(p_c) at φ = φ0.
template <typename Real>
CASCADE_HD inline Real saturation_at_porosity(const HydraulicModel<Real>& curve, Real reference_porosity, Real p_c,
                                              Real porosity) {
  const Real bound = grain_bound_saturation(curve, reference_porosity, porosity);
  return bound + (curve.saturation_max() - bound) * curve.effective_saturation(p_c);
}

// ∂S_w/∂p_c at constant φ: (S_max − S_b(φ)) dS_e/dp_c.
template <typename Real>
CASCADE_HD inline Real saturation_derivative_at_porosity(const HydraulicModel<Real>& curve, Real reference_porosity,
                                                         Real p_c, Real porosity) {
  const Real free_range = curve.saturation_max() - grain_bound_saturation(curve, reference_porosity, porosity);
  return free_range / (curve.saturation_max() - curve.bound_saturation()) * curve.saturation_derivative(p_c);
}

// C_r = φ (S_w − K_w ∂S_w/∂p_c) (Eqs. 28b and 41, ERRATA.md row "Eq. 28b / 41"), the storage
// factor of the pore-water continuity (Eqs. 3a, 27a) and c_v of the seepage time step (Eq. 40c),
// at the particle's porosity. K_w is the water bulk modulus of the pore-water equation of state
// (Section 2.2). It follows from ∂(φ S_w ρ_w)/∂t with ∂p_w = (K_w/ρ_w) ∂ρ_w and
// ∂S_w/∂p_w = −∂S_w/∂p_c: since ∂S_w/∂p_c <= 0, C_r >= φ S_w.
template <typename Real>
CASCADE_HD inline Real pore_water_capacity(const HydraulicModel<Real>& curve, Real reference_porosity, Real p_c,
                                           Real porosity, Real water_bulk_modulus) {
  return porosity * (saturation_at_porosity(curve, reference_porosity, p_c, porosity) -
                     water_bulk_modulus * saturation_derivative_at_porosity(curve, reference_porosity, p_c, porosity));
}

// S_max S_e(p_c): the factor of the skeleton's ε̇_v in the pore-water continuity (Eq. 27a as
// derived above).
template <typename Real>
CASCADE_HD inline Real skeleton_water_share(const HydraulicModel<Real>& curve, Real p_c) {
  return curve.saturation_max() * curve.effective_saturation(p_c);
}

}  // namespace cascade
