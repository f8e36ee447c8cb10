// The pore-water state of a soil particle before its neighbour passes: pressure from its pore
// water density (Eq. 6 with the soil's K_w), the free-surface hydraulic condition (Eq. 39 with
// ERRATA.md) and the saturation S_w(p_c), p_c = −p_w (Section 2.2: zero pore-air pressure).
//
// Eq. 39's adaptive switch, per free-surface particle, decided at the first evaluation of a step
// from the state the previous step left:
//  - flux: q_w is prescribed, (0, ..., −i) with i the rainfall intensity inside the rain region
//    and 0 outside it (seepage.h). Reaching p_w >= p_max it ponds (with or without rain: water
//    that seeps out of the surface leaves it at p_max); evaporating, reaching p_w <= p_min it dries.
//  - ponded: p_w = p_max is prescribed and q_w follows Eq. 27b; once the soil takes more than
//    the rain (−q_z > i) the particle returns to the flux condition.
//  - drying: p_w = p_min is prescribed; once the soil delivers more than the evaporation demand
//    (q_z > −i, or rain again) the particle returns to the flux condition.
//  - held: while the forcing prescribes a surface pressure, every free-surface particle holds it
//    (a Dirichlet condition) and q_w follows Eq. 27b; once it no longer does, the particle takes
//    the switch above from its held pressure.
// A particle that leaves the free surface returns to the flux state.
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/hydraulic_forcing.h"
#include "server/core/particle_view.h"
#include "server/physics/soil_view.h"
#include "server/physics/swcc/grain_bound_water.h"

namespace cascade {

// The part of HydraulicForcing the kernels read, in the engine's precision.
template <typename Real, int Dim>
struct SurfaceForcing {
  Real intensity;        // m/s into the soil
  Real ponding;          // p_max (Pa)
  Real drying;           // p_min (Pa), may be −∞
  bool has_surface_pressure;
  Real surface_pressure;  // Pa, held by every free-surface particle when has_surface_pressure
  bool has_region;
  Vec<Real, Dim> region_min, region_max;

  static SurfaceForcing from(const HydraulicForcing& f) {
    SurfaceForcing s{Real(f.rainfall_intensity), Real(f.ponding_pressure), Real(f.drying_pressure),
                     f.has_surface_pressure, Real(f.surface_pressure), f.has_region, Vec<Real, Dim>::Zero(),
                     Vec<Real, Dim>::Zero()};
    for (int a = 0; a < Dim; ++a) {
      s.region_min[a] = Real(f.region_min[a]);
      s.region_max[a] = Real(f.region_max[a]);
    }
    return s;
  }

  // The intensity on a surface particle at x: i inside the rain region, 0 outside.
  CASCADE_HD Real intensity_at(const Vec<Real, Dim>& x) const {
    if (!has_region) return intensity;
    for (int a = 0; a < Dim; ++a)
      if (x[a] < region_min[a] || x[a] > region_max[a]) return Real(0);
    return intensity;
  }
};

template <typename Real, int Dim>
struct PoreWaterState {
  ParticleView<Real, Dim> p;
  SoilView<Real, Dim> soil;
  SurfaceForcing<Real, Dim> forcing;
  Real rho0;
  bool update_states;  // the first evaluation of a step decides the surface states

  CASCADE_HD void operator()(std::uint32_t i) const {
    const SoilMaterial& m = soil.materials[soil.material[i]];
    Real pressure = pore_pressure(m, rho0, p.water_density[i]);
    std::uint8_t state = soil.surface_state[i];
    if (update_states) state = next_state(i, pressure);
    if (state == std::uint8_t(SurfaceState::ponded)) pressure = forcing.ponding;
    if (state == std::uint8_t(SurfaceState::drying)) pressure = forcing.drying;
    if (state == std::uint8_t(SurfaceState::held)) pressure = forcing.surface_pressure;
    if (state != std::uint8_t(SurfaceState::flux)) p.water_density[i] = pore_density_of(m, rho0, pressure);  // Eq. 36b
    soil.surface_state[i] = state;
    p.pressure[i] = pressure;
    soil.saturation[i] =
        Real(saturation_at_porosity(m.hydraulic, m.reference_porosity, -double(pressure), double(soil.porosity[i])));
  }

 private:
  CASCADE_HD std::uint8_t next_state(std::uint32_t i, Real pressure) const {
    if (!soil.free_surface[i]) return std::uint8_t(SurfaceState::flux);
    if (forcing.has_surface_pressure) return std::uint8_t(SurfaceState::held);
    const Real intensity = forcing.intensity_at(p.position[i]);
    const Real q_up = soil.seepage[i][Dim - 1];  // Eq. 27b's discharge of the last evaluation
    switch (SurfaceState(soil.surface_state[i])) {
      case SurfaceState::ponded:
        return -q_up > intensity ? std::uint8_t(SurfaceState::flux) : std::uint8_t(SurfaceState::ponded);
      case SurfaceState::drying:
        return (intensity >= Real(0) || q_up > -intensity) ? std::uint8_t(SurfaceState::flux)
                                                           : std::uint8_t(SurfaceState::drying);
      case SurfaceState::flux:
      case SurfaceState::held:
        break;
    }
    if (pressure >= forcing.ponding) return std::uint8_t(SurfaceState::ponded);  // also a seepage face
    if (pressure <= forcing.drying && intensity < Real(0)) return std::uint8_t(SurfaceState::drying);
    return std::uint8_t(SurfaceState::flux);
  }
};

}  // namespace cascade
