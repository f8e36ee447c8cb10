// Kinematics of the soil stress update: strain rate and spin from the velocity gradient
// (Eqs. 9a, 9b; their SPH forms are Eqs. 26c, 26d) and the rotation part of the Jaumann stress
// rate (Eq. 8), which keeps the stress objective under rigid-body rotation.
#pragma once

#include "server/core/types.h"

namespace cascade {

// The velocity gradient as a full 3D tensor, L_ab = ∂v_a/∂x_b: the index order of Eqs. 26c/26d,
// whose sums Σ_j V_j (v_j^α − v_i^α) ∂W_ij/∂x_i^β approximate ∂v^α/∂x^β. A 2D case lives in the
// plane (x, z) (docs/physics.md, Notation), so its 2×2 gradient over (x, z) goes to rows and
// columns 0 and 2; the out-of-plane row and column stay zero (plane strain: ε̇_yy = 0, no spin
// about x or z).
template <typename Real, int Dim>
CASCADE_HD inline Mat<Real, 3> velocity_gradient_3d(const Mat<Real, Dim>& grad_v) {
  static_assert(Dim == 2 || Dim == 3, "2D (x, z) or 3D");
  if constexpr (Dim == 3) {
    return grad_v;
  } else {
    Mat<Real, 3> l = Mat<Real, 3>::Zero();
    l(0, 0) = grad_v(0, 0);
    l(0, 2) = grad_v(0, 1);
    l(2, 0) = grad_v(1, 0);
    l(2, 2) = grad_v(1, 1);
    return l;
  }
}

// Eq. 9a (SPH form Eq. 26c): ε̇ = ½ (L + Lᵀ).
template <typename Real>
CASCADE_HD inline Mat<Real, 3> strain_rate(const Mat<Real, 3>& grad_v) {
  return Real(0.5) * (grad_v + grad_v.transpose());
}

// Eq. 9b (SPH form Eq. 26d): ω = ½ (L − Lᵀ), ω_ab = ½ (∂v_a/∂x_b − ∂v_b/∂x_a). For a rigid
// rotation v = Ω × x this is ω x = Ω × x, i.e. ω = Ṙ Rᵀ.
template <typename Real>
CASCADE_HD inline Mat<Real, 3> spin_rate(const Mat<Real, 3>& grad_v) {
  return Real(0.5) * (grad_v - grad_v.transpose());
}

// Rotation part of the Jaumann rate, σ·ωᵀ + ω·σ = ω·σ − σ·ω for the antisymmetric ω of Eq. 26d
// (Bui et al. 2008: σ^αγ ω̇^βγ + σ^γβ ω̇^αγ). Eq. 8 is printed as −dω·σ + σ·dω, the opposite
// sign for this ω; only ω·σ − σ·ω makes a stress carried by a rigid rotation R = exp(ω t) equal
// R σ₀ Rᵀ (dσ/dt = Ṙσ₀Rᵀ + Rσ₀Ṙᵀ = ωσ − σω), which test_soil_models.cpp checks
// (docs/physics.md, "Soil constitutive models"). Takes a spin rate or a spin increment ω Δt alike;
// the result is symmetric when σ is.
template <typename Real>
CASCADE_HD inline Mat<Real, 3> jaumann_rotation(const Mat<Real, 3>& stress, const Mat<Real, 3>& spin) {
  return spin * stress - stress * spin;
}

// Eq. 8 as a rate: dσ/dt = σ̇_constitutive + ω·σ − σ·ω, where σ̇_constitutive = D^ep : ε̇ is the
// objective (co-rotational) rate that the constitutive model gives.
template <typename Real>
CASCADE_HD inline Mat<Real, 3> jaumann_stress_rate(const Mat<Real, 3>& constitutive_rate, const Mat<Real, 3>& stress,
                                                   const Mat<Real, 3>& spin) {
  return constitutive_rate + jaumann_rotation(stress, spin);
}

}  // namespace cascade
