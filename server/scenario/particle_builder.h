// Scenario → initial particles: water or soil particles on a global lattice filling the FLUID
// bodies (by their material), and
// the dummy particles of the BOUNDARY bodies with their ghost nodes (paper Section 3.3.1; set up
// the way DualSPHysics' mDBC does it: each dummy particle b is mirrored into the fluid across the
// closest point of the wetted solid surface).
//
// Lattice: points ((i + 1/2) dp, (j + 1/2) dp, (k + 1/2) dp) for integers i, j, k (2D: (x, z) only),
// so a wall at a multiple of dp has its first fluid layer at dp/2 and its first dummy layer at -dp/2.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "server/core/host_particles.h"

namespace cascade::v1 {
class ScenarioSpec;
}

namespace cascade {

// What the builder made of one body.
struct BodyReport {
  std::string name;
  std::size_t first = 0;        // index of its first particle
  std::size_t count = 0;        // its particles (water, soil or dummy)
  double thickness = 0.0;       // BOUNDARY: depth of the dummy layers below the wetted surface (m)
  double wetted_surface = 0.0;  // BOUNDARY: length (2D) or area (3D) of its wetted surface in the domain
};

struct ParticleSet {
  HostParticles particles;
  std::vector<BodyReport> bodies;  // one per ScenarioSpec.bodies, same order
};

// Above this many particles (estimated from the bodies' bounding boxes before anything is
// generated) the builder refuses the case.
constexpr double kMaxParticles = 5e7;

// Builds the initial particles. Particles come body by body in spec order, each body's in
// (z, y, x) lexicographic lattice order, so the result is deterministic.
//  - FLUID: lattice points in the body's region, outside every BOUNDARY body's solid and not in an
//    earlier FLUID body's region (list a soil body before the water over it). Water: density ρ_w0,
//    or hydrostatic (`initial.hydrostatic`): ρ_w = ρ_w0 + ρ_w0 |g| (z_top - z) / c_w0², z_top = the
//    body's highest particle + dp/2 (Eq. 6). Soil (phase soil): porosity φ0, soil_material the
//    index among the case's soil materials, pore pressure p_w from `initial` (suction or water
//    table) as the pore-water density ρ_w = ρ_w0 (1 + p_w/K_w) (Eq. 36b), and the geostatic
//    effective stress of InitialState.k0 in scenario.proto. Other particles get porosity 0 and a
//    zero effective stress. ρ_w0 is the case's (reference_water_density, soil_setup.h).
//    Soil bodies are wetted like water bodies: walls under and beside them get dummy layers.
//  - BOUNDARY: lattice points in the body's solid, not taken by an earlier BOUNDARY body, closer
//    than `boundary_thickness` to the wetted surface, i.e. the surface of all solids that is neither
//    covered by another solid nor facing out of the domain. Ghost node x_g = 2 s - x_b with s the
//    closest wetted point (a plane mirror across faces, a point reflection through edges/corners).
// Throws CaseError naming the offending key.
ParticleSet build_particle_set(const v1::ScenarioSpec& spec);
HostParticles build_particles(const v1::ScenarioSpec& spec);

// h = h_over_dp · dp (h_over_dp 0 means 1.3).
double smoothing_length(const v1::ScenarioSpec& spec);

// Depth of a BOUNDARY body's dummy layers: layers · dp, or (layers 0) the kernel support 2h
// rounded up to whole layers.
double boundary_thickness(const v1::ScenarioSpec& spec, int body_index);

// c_w0 of a water material (Eq. 24a): its sound_speed if set, else
// 10 max(v_max, sqrt(Δp_max / ρ_w0)) with v_max = max_speed or sqrt(2 |g| H) and
// Δp_max = max_pressure or ρ_w0 |g| H, where H spans all water particles (their highest top minus
// lowest bottom, each dp/2 beyond the particle). The engine must use the same value.
double water_sound_speed(const v1::ScenarioSpec& spec, int material_index, const HostParticles& particles);

}  // namespace cascade
