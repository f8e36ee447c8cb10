// Isotropic linear elasticity in rate form: the elastic part of D^ep in Eq. 8. The paper names
// its moduli only through K and G (Eq. 29); case files give E and ν.
#pragma once

#include "server/core/types.h"
#include "server/physics/soil/jaumann_rate.h"

namespace cascade {

template <typename Real>
struct LinearElastic {
  Real bulk_modulus;   // K [Pa]
  Real shear_modulus;  // G [Pa]

  // K = E / (3(1 − 2ν)), G = E / (2(1 + ν)): finite and positive for E > 0, −1 < ν < 0.5, the
  // range SoilModel::validate() enforces.
  CASCADE_HD static LinearElastic from_young_poisson(Real youngs_modulus, Real poisson_ratio) {
    return {youngs_modulus / (Real(3) * (Real(1) - Real(2) * poisson_ratio)),
            youngs_modulus / (Real(2) * (Real(1) + poisson_ratio))};
  }

  // Lamé's λ = K − 2G/3.
  CASCADE_HD Real lame_lambda() const { return bulk_modulus - Real(2) / Real(3) * shear_modulus; }

  // Hooke's law, dσ = 2G dε + λ tr(dε) I; the same for rates (σ̇ from ε̇) and for increments
  // (dσ from dε = ε̇ Δt), since it is linear.
  CASCADE_HD Mat<Real, 3> stress_increment(const Mat<Real, 3>& strain_increment) const {
    return Real(2) * shear_modulus * strain_increment +
           (lame_lambda() * strain_increment.trace()) * Mat<Real, 3>::Identity();
  }

  // The strain of a stress, dε = ds/(2G) + tr(dσ)/(9K) I: the inverse of stress_increment, which
  // the tests use to recover plastic strains.
  CASCADE_HD Mat<Real, 3> strain_increment(const Mat<Real, 3>& stress_increment) const {
    const Real mean = stress_increment.trace() / Real(3);
    const Mat<Real, 3> deviator = stress_increment - mean * Mat<Real, 3>::Identity();
    return deviator / (Real(2) * shear_modulus) + (mean / (Real(3) * bulk_modulus)) * Mat<Real, 3>::Identity();
  }

  // One explicit step of Eq. 8 with D^ep = D^e: σ_new = σ + dω·σ − σ·dω + D^e : dε, with the
  // increments dε = ε̇Δt, dω = ω̇Δt and the rotation taken with the stress at the start of the step.
  CASCADE_HD Mat<Real, 3> update(const Mat<Real, 3>& stress, const Mat<Real, 3>& strain_increment,
                                 const Mat<Real, 3>& spin_increment) const {
    return stress + jaumann_rotation(stress, spin_increment) + stress_increment(strain_increment);
  }
};

}  // namespace cascade
