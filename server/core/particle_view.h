// Raw pointers into the particle arrays, handed to kernels by value at each launch.
#pragma once

#include <cstdint>

#include "server/core/kernel.h"
#include "server/core/types.h"

namespace cascade {

template <typename Real, int Dim>
struct ParticleView {
  Vec<Real, Dim>* position;
  Vec<Real, Dim>* velocity;
  Real* density;                       // numerical density ρ (Eq. 22); volume V = m / ρ
  Real* water_density;                 // ρ_w (Eq. 23a); pressure through Eq. 6
  Real* pressure;                      // p_w
  const Phase* phase;
  const Vec<Real, Dim>* ghost;         // ghost node of a boundary particle
  Vec<Real, Dim>* acceleration;        // dv/dt
  Real* density_rate;                  // dρ/dt
  Real* water_density_rate;            // dρ_w/dt
  Vec<Real, Dim>* water_density_gradient;  // renormalised ⟨∇ρ_w⟩^L (Eq. 25a)
  Real* step_limit;                    // per-particle min(Δt_cv, Δt_f) before C0 (Eq. 40)
};

// Constants of the SPH discretisation shared by every term.
template <typename Real, int Dim>
struct SphConstants {
  WendlandC2<Real, Dim> kernel;
  Real h;
  Real eta2;                           // η² = (0.1 h)² (Eq. 24b-c)
  Real laplacian_scale;                // m/m_η of the lattice: the pairwise Laplacian exact there (seepage_exchange.h)
  Real dp;                             // the initial particle spacing
  Real mass;                           // m = ρ_w0 dp^Dim, the same for every particle (Section 3.2)
  Vec<Real, Dim> gravity;
};

}  // namespace cascade
