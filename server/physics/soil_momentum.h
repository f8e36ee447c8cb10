// Soil momentum (Eq. 26b) with Bishop's total stress (Eq. 7), the mixture density (Eq. 28a) and
// the soil sound speed (Eq. 29).
#pragma once

#include <cmath>

#include "server/core/soil_material.h"
#include "server/core/types.h"

namespace cascade {

// Symmetric tensors as 6 Voigt components xx, yy, zz, xy, yz, zx (docs/output.md); 3D always,
// also in 2D cases, whose plane is (x, z) with y out of plane.
template <typename Real>
using Voigt = Eigen::Matrix<Real, 6, 1>;

template <typename Real>
CASCADE_HD inline Mat<Real, 3> tensor_of(const Voigt<Real>& v) {
  Mat<Real, 3> t;
  t << v(0), v(3), v(5), v(3), v(1), v(4), v(5), v(4), v(2);
  return t;
}
template <typename Real>
CASCADE_HD inline Voigt<Real> voigt_of(const Mat<Real, 3>& t) {
  Voigt<Real> v;
  v << t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(1, 2), t(2, 0);
  return v;
}

// The in-plane part of a 3D tensor: all of it in 3D, rows and columns (x, z) in 2D.
template <typename Real, int Dim>
CASCADE_HD inline Mat<Real, Dim> in_plane(const Voigt<Real>& v) {
  if constexpr (Dim == 3) {
    return tensor_of(v);
  } else {
    Mat<Real, 2> t;
    t << v(0), v(5), v(5), v(2);
    return t;
  }
}

// Eq. 7: σ = σ' − S_w p_w I, tension positive.
template <typename Real>
CASCADE_HD inline Voigt<Real> total_stress(const Voigt<Real>& effective, Real saturation, Real pore_pressure) {
  Voigt<Real> s = effective;
  for (int a = 0; a < 3; ++a) s(a) -= saturation * pore_pressure;
  return s;
}

// Eq. 28a: ρ_s = (1 − φ) ρ_s0 + S_w φ ρ_w0.
template <typename Real>
CASCADE_HD inline Real mixture_density(const SoilMaterial& m, Real porosity, Real saturation, Real rho_w0) {
  return (Real(1) - porosity) * Real(m.grain_density) + saturation * porosity * rho_w0;
}

// The skeleton's P-wave modulus K + 4G/3, with K and G of the elastic part of the soil model.
CASCADE_HD inline double skeleton_p_wave_modulus(const SoilMaterial& m) {
  const auto e = m.mechanical.elastic();
  return 4.0 * e.shear_modulus / 3.0 + e.bulk_modulus;
}

// Eq. 29: c_s0 = sqrt((4G/3 + K)/ρ_s0).
CASCADE_HD inline double soil_sound_speed(const SoilMaterial& m) {
  return std::sqrt(skeleton_p_wave_modulus(m) / m.grain_density);
}

// The P-wave speed of the soil with its pore water, for the step limit of Eq. 40b:
//   c_s = sqrt((K + 4G/3 + S_w S K_w / C_r) / ρ_s),
// the skeleton's (Eq. 29) stiffened by the pore water, which in an undrained compression takes
// dp_w = −(S K_w / C_r) dε_v (Eq. 27a without flow, S = S_max S_e the skeleton's share of the pore
// water, grain_bound_water.h) and adds −S_w dp_w to the total stress (Eq. 7); ρ_s of Eq. 28a.
// Eq. 29's c_s0 leaves the pore water out: with the tables' K_w = 2 MPa it adds about 40% stiffness
// to a 10 MPa skeleton, with K_w = 20 MPa a saturated layer went unstable at the Eq. 29 step, and
// with real water (2.2 GPa) the wave is some 20 times faster.
CASCADE_HD inline double undrained_sound_speed(const SoilMaterial& m, double saturation, double skeleton_share,
                                               double capacity, double mixture_density) {
  const double pore_stiffness = capacity > 0 ? saturation * skeleton_share * m.water_bulk_modulus / capacity : 0.0;
  return std::sqrt((skeleton_p_wave_modulus(m) + pore_stiffness) / mixture_density);
}

// One neighbour's V_j (σ_i + σ_j)·∇_i W_ij of Eq. 26b, with the in-plane total stresses; the sum is
// divided by ρ_s,i. Written with V_j = m/ρ_j and ρ_s V_i the mass of particle i, the pair force
// V_i V_j (σ_i + σ_j)·∇_i W_ij is antisymmetric: the soil conserves momentum.
template <typename Real, int Dim>
CASCADE_HD inline Vec<Real, Dim> stress_force_pair(Real volume_j, const Mat<Real, Dim>& stress_sum,
                                                   const Vec<Real, Dim>& grad_w) {
  return volume_j * (stress_sum * grad_w);
}

}  // namespace cascade
