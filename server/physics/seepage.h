// Seepage discharge of the pore water (Eq. 27b):
//   q_w,i = K_i/g ( −(1/ρ_w,i) ⟨∇p_w⟩_i + g − a_s,i ),
// K_i = K_sat K_rel(p_c,i) (Eqs. 15, 42b, 43b), with the renormalised pressure gradient of
// renormalised_gradient.h, which that pass leaves in the seepage array itself. The drag between
// the pore water and the skeleton is this K term (ERRATA.md); free water particles do not take
// part (no mass exchange between free water and pore water). a_s is the skeleton's acceleration
// low-passed over the last steps (seepage_inertia.h), zero for a rigid skeleton. A free-surface
// particle under the flux condition of Eq. 39 takes the prescribed discharge (0, ..., −i) instead
// (pore_water_state.h).
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/particle_view.h"
#include "server/physics/pore_water_state.h"
#include "server/physics/soil_view.h"

namespace cascade {

template <typename Real, int Dim>
struct SeepageDischarge {
  ParticleView<Real, Dim> p;
  SoilView<Real, Dim> soil;
  SphConstants<Real, Dim> sph;
  SurfaceForcing<Real, Dim> forcing;

  CASCADE_HD void operator()(std::uint32_t i) const {
    const SoilMaterial& m = soil.materials[soil.material[i]];
    const Real conductivity =
        Real(m.saturated_conductivity * m.hydraulic.relative_conductivity(-double(p.pressure[i])));
    soil.conductivity[i] = conductivity;  // for the pair exchanges of the continuity (seepage_exchange.h)
    if (soil.free_surface[i] && soil.surface_state[i] == std::uint8_t(SurfaceState::flux)) {
      Vec<Real, Dim> q = Vec<Real, Dim>::Zero();
      q[Dim - 1] = -forcing.intensity_at(p.position[i]);
      soil.seepage[i] = q;
      return;
    }
    const Real g = sph.gravity.norm();
    const Vec<Real, Dim> pressure_gradient = soil.seepage[i];  // left there by the gradient pass
    soil.seepage[i] =
        conductivity / g * (-pressure_gradient / p.water_density[i] + sph.gravity - soil.skeleton_acceleration[i]);
  }
};

}  // namespace cascade
