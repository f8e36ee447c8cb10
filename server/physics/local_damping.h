// Dynamic relaxation of the geostatic stage (docs/physics.md, "Geostatic start"): gravity is
// brought to equilibrium with the initial stresses by running the explicit step with Cundall's
// local non-viscous damping on the soil skeleton (Cundall 1987, "Distinct element models of rock
// and soil structure", in Brown (ed.), Analytical and Computational Methods in Engineering Rock
// Mechanics, Allen & Unwin; the "local damping" of Itasca's FLAC, PFC and UDEC). Per particle and
// per component k of the acceleration a_i of Eq. 26b (gravity included):
//   a_i,k ← a_i,k − α |a_i,k| sign(v_i,k),   0 <= α < 1,  sign(0) = 0,
// a force against the motion in proportion to the unbalanced force, not to the velocity: it takes
// out energy where a particle accelerates and none at a steady state, and it needs no frequency
// (a viscous damping would have to be tuned to the slope's lowest mode). α = 0 leaves a_i as it
// is. While relaxing the free water is damped too (simulation.h): the lake a slope stands in must
// come to rest with it, or its sloshing keeps loading the soil beside it. A rigid skeleton has
// a_i = 0.
//
// The equilibrium measure of the stage: the unbalanced force on soil particle i is its undamped
// net force F_i = m_i a_i with m_i = ρ_s,i V_i (Eq. 28a, V_i = m/ρ_i of Eq. 22); the stage
// reports max_i |F_i| / mean_i m_i |g| over the non-rigid soil particles (the FLAC "maximum
// unbalanced force ratio" with the mean gravity force of a particle as the scale) and the largest
// soil speed max_i |v_i|.
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/particle_view.h"
#include "server/core/soil_material.h"
#include "server/physics/soil_momentum.h"

namespace cascade {

// a_i after Cundall's local damping with coefficient α, as above.
template <typename Real, int Dim>
CASCADE_HD inline Vec<Real, Dim> locally_damped_acceleration(const Vec<Real, Dim>& acceleration,
                                                             const Vec<Real, Dim>& velocity, Real alpha) {
  Vec<Real, Dim> damped = acceleration;
  for (int k = 0; k < Dim; ++k) {
    const Real direction = velocity[k] > Real(0) ? Real(1) : (velocity[k] < Real(0) ? Real(-1) : Real(0));
    damped[k] -= alpha * std::fabs(acceleration[k]) * direction;
  }
  return damped;
}

// Per soil (and, while relaxing, water) particle, after its interaction pass: keeps |a_i| before
// damping (the unbalanced acceleration of the equilibrium measure, read over the soil) and damps
// a_i. Run on every step, with α = 0 outside the geostatic stage, so that the measure is that of
// the engine's last step in every stage.
template <typename Real, int Dim>
struct LocalDamping {
  ParticleView<Real, Dim> p;
  Real* unbalanced_acceleration;  // per soil particle: |a_i| before damping
  Real alpha;

  CASCADE_HD void operator()(std::uint32_t i) const {
    const Vec<Real, Dim> a = p.acceleration[i];
    unbalanced_acceleration[i] = a.norm();
    p.acceleration[i] = locally_damped_acceleration<Real, Dim>(a, p.velocity[i], alpha);
  }
};

// The sums of the equilibrium measure over a set of soil particles.
template <typename Real>
struct EquilibriumSums {
  Real max_force;     // max |F_i| (N per unit thickness in 2D)
  Real weight;        // Σ m_i |g|
  Real particles;     // how many non-rigid soil particles
  Real max_speed;     // max |v_i|
};

template <typename Real>
struct CombineEquilibriumSums {
  CASCADE_HD EquilibriumSums<Real> operator()(const EquilibriumSums<Real>& a, const EquilibriumSums<Real>& b) const {
    return {a.max_force > b.max_force ? a.max_force : b.max_force, a.weight + b.weight, a.particles + b.particles,
            a.max_speed > b.max_speed ? a.max_speed : b.max_speed};
  }
};

// One soil particle's part of the measure; nothing for a rigid skeleton.
template <typename Real, int Dim>
struct EquilibriumOfParticle {
  const SoilMaterial* materials;
  const std::uint8_t* material;
  const Real* porosity;
  const Real* saturation;
  const Real* density;  // numerical density ρ (Eq. 22)
  const Vec<Real, Dim>* velocity;
  const Real* unbalanced_acceleration;
  Real particle_mass;  // m of SphConstants
  Real gravity;        // |g|
  Real rho0;           // ρ_w0

  CASCADE_HD EquilibriumSums<Real> operator()(std::uint32_t i) const {
    const SoilMaterial& m = materials[material[i]];
    if (m.rigid) return {Real(0), Real(0), Real(0), Real(0)};
    const Real mass = mixture_density(m, porosity[i], saturation[i], rho0) * particle_mass / density[i];
    return {mass * unbalanced_acceleration[i], mass * gravity, Real(1), velocity[i].norm()};
  }
};

}  // namespace cascade
