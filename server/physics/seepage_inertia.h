// The skeleton acceleration a_s that the seepage discharge of Eq. 27b takes, low-passed over a
// time τ = kSeepageInertiaWaves h / c_s0 (c_s0 of Eq. 29):
//   ā_s ← ā_s + Δt/(τ + Δt) (a_s − ā_s),   once per step, with a_s of the step's last evaluation.
//
// Why: Eq. 27b with a_s, beside a mixture momentum (Eq. 26b) that carries no relative fluid
// acceleration, is the u-p approximation of Biot's equations, valid for slow motion (Zienkiewicz
// et al. 1980). For elastic waves its energy balance has a term ∝ (K/g) p_w' σ'' of no sign: the
// dispersion relation of the 1D equations (docs/physics.md, "Skeleton acceleration in the
// seepage") gives waves of wavenumber k a growth rate ≈ (K/g) c² k² ρ_w/(2ρ_s), which at the
// particle scale outgrew the soil's artificial viscosity from K_sat ≈ 3e-4 m/s (a saturated
// column blew up from round-off). Low-passed over τ = 100 h/c_s0, a_s keeps the slow
// accelerations of a sliding or settling mass, for which Eq. 27b is meant, and drops those of
// waves (every mode k ≥ 3/m of that relation then decays for K up to 1e-2 m/s); quasi-static
// problems have a_s ≈ 0 either way.
#pragma once

#include <cstdint>

#include "server/core/particle_view.h"
#include "server/physics/soil_momentum.h"
#include "server/physics/soil_view.h"

namespace cascade {

constexpr double kSeepageInertiaWaves = 100.0;  // τ in units of h/c_s0

template <typename Real, int Dim>
struct SeepageInertiaFilter {
  ParticleView<Real, Dim> p;
  SoilView<Real, Dim> soil;
  Real h;
  Real dt;

  CASCADE_HD void operator()(std::uint32_t i) const {
    const SoilMaterial& m = soil.materials[soil.material[i]];
    if (m.rigid) return;  // a_s = 0 (set up so)
    const Real tau = Real(kSeepageInertiaWaves) * h / Real(soil_sound_speed(m));
    const Real weight = dt / (tau + dt);
    soil.skeleton_acceleration[i] += weight * (p.acceleration[i] - soil.skeleton_acceleration[i]);
  }
};

}  // namespace cascade
