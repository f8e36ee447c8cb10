// Velocity damping of the soil skeleton, for quasi-static loading of elastic columns (Section 4.2:
// "the viscous dissipation term proposed by Feng et al. (2024b) with a viscous coefficient of
// 0.1 ... to suppress the oscillations in the SPH simulation of elastic materials").
//
// The paper gives neither the formula of Feng et al. (2024b) nor its reference, and it could not
// be found; this term stands in for it: the damping force of Bui and Fukagawa (2013, and Bui et
// al. 2008's geostatic initialisation), per unit mass
//   a_d,i = −c_d v_i,   c_d = ξ sqrt(E / (ρ_s,i h²)),
// with ξ the material's coefficient (SoilMaterial::damping), E Young's modulus and ρ_s,i the
// mixture density (Eq. 28a). sqrt(E/ρ_s)/h is about the highest frequency the particle lattice
// carries, so ξ is a fraction of critical damping of the shortest waves; the long, slow motion of
// consolidation is slowed by c_d too, which is why it is for quasi-static problems only and off
// (ξ = 0) by default. It is added to the acceleration of Eq. 26b (soil_interaction.h), and so to
// the a_s of the seepage discharge (Eq. 27b). Explicit stability needs c_d Δt < 2: the step of
// Eq. 40b, Δt <= C0 h/c_s with the P-wave speed c_s = sqrt((K + 4G/3)/ρ_s0) (soil_momentum.h),
// gives c_d Δt <= C0 ξ sqrt(E ρ_s0/((K + 4G/3) ρ_s)), about C0 ξ: far below for ξ of order 1.
#pragma once

#include <cmath>

#include "server/core/soil_material.h"
#include "server/core/types.h"

namespace cascade {

// −c_d v_i of the term above; zero when the material's ξ is 0.
template <typename Real, int Dim>
CASCADE_HD inline Vec<Real, Dim> soil_damping_acceleration(const SoilMaterial& m, Real mixture_density, Real h,
                                                          const Vec<Real, Dim>& velocity) {
  if (!(m.damping > 0)) return Vec<Real, Dim>::Zero();
  const Real c_d = Real(m.damping * std::sqrt(m.mechanical.youngs_modulus / double(mixture_density))) / h;
  return -c_d * velocity;
}

}  // namespace cascade
