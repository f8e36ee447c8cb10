// Symplectic Position Verlet (Section 3.4, as in DualSPHysics, Domínguez et al. 2022): rates at
// step n give the half-step state, rates at the half step give the full step:
//   predictor  x^{n+½} = x^n + ½Δt v^n,  v^{n+½} = v^n + ½Δt a^n,  ρ^{n+½} = ρ^n + ½Δt (dρ/dt)^n
//   corrector  v^{n+1} = v^n + Δt a^{n+½},  x^{n+1} = x^n + ½Δt (v^n + v^{n+1}),
//              ρ^{n+1} = ρ^n (2 − ε)/(2 + ε),  ε = −(dρ/dt)^{n+½} Δt / ρ^{n+½}
// Dummy boundary particles stay where they are; their values come from the ghost nodes.
#pragma once

#include <cstdint>

#include "server/core/neighbour_grid.h"
#include "server/core/particle_view.h"

namespace cascade {

// The state at the start of the step, kept for the corrector.
template <typename Real, int Dim>
struct StepStartState {
  const Vec<Real, Dim>* position;
  const Vec<Real, Dim>* velocity;
  const Real* density;
  const Real* water_density;
};

template <typename Real>
CASCADE_HD inline Real symplectic_density(Real start, Real half, Real rate, Real dt) {
  const Real epsilon = -rate / half * dt;
  return start * (Real(2) - epsilon) / (Real(2) + epsilon);
}

template <typename Real, int Dim>
struct SymplecticPredictor {
  ParticleView<Real, Dim> p;
  StepStartState<Real, Dim> start;
  GridView<Real, Dim> grid;
  Real dt;

  CASCADE_HD void operator()(std::uint32_t i) const {
    if (p.phase[i] == Phase::boundary) return;
    const Real half = Real(0.5) * dt;
    Vec<Real, Dim> x = start.position[i] + half * start.velocity[i];
    grid.wrap(x);
    p.position[i] = x;
    p.velocity[i] = start.velocity[i] + half * p.acceleration[i];
    p.density[i] = start.density[i] + half * p.density_rate[i];
    p.water_density[i] = start.water_density[i] + half * p.water_density_rate[i];
  }
};

template <typename Real, int Dim>
struct SymplecticCorrector {
  ParticleView<Real, Dim> p;
  StepStartState<Real, Dim> start;
  GridView<Real, Dim> grid;
  Real dt;

  CASCADE_HD void operator()(std::uint32_t i) const {
    if (p.phase[i] == Phase::boundary) return;
    const Vec<Real, Dim> v = start.velocity[i] + dt * p.acceleration[i];
    Vec<Real, Dim> x = start.position[i] + (Real(0.5) * dt) * (start.velocity[i] + v);
    grid.wrap(x);
    p.position[i] = x;
    p.velocity[i] = v;
    p.density[i] = symplectic_density(start.density[i], p.density[i], p.density_rate[i], dt);
    p.water_density[i] = symplectic_density(start.water_density[i], p.water_density[i], p.water_density_rate[i], dt);
  }
};

}  // namespace cascade
