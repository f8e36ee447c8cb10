#include "server/scenario/engine_setup.h"

#include <string>
#include <vector>

#include "server/scenario/case_error.h"
#include "server/scenario/particle_builder.h"
#include "server/scenario/soil_setup.h"

namespace cascade {

EngineConfig engine_config(const v1::ScenarioSpec& spec, const HostParticles& particles, Precision precision,
                           Device device) {
  EngineConfig c;
  c.dimensions = spec.dimensions();
  c.dp = spec.dp();
  c.h = smoothing_length(spec);
  for (int a = 0; a < c.dimensions; ++a) {
    c.gravity[a] = a < spec.gravity_size() ? spec.gravity(a) : 0.0;
    c.domain_min[a] = spec.domain().min(a);
    c.domain_max[a] = spec.domain().max(a);
    c.periodic[a] = a < spec.domain().periodic_size() && spec.domain().periodic(a);
  }
  int water = -1;
  for (int m = 0; m < spec.materials_size(); ++m) {
    if (!spec.materials(m).has_water()) continue;
    // The engine holds one set of water constants (ρ_w0, c_w0, δ, α): a second water material
    // would start in a state its equation of state does not balance.
    if (water >= 0)
      throw CaseError("materials[" + std::to_string(m) + "]", "a case has one water material; '" +
                                                             spec.materials(water).name() + "' is already one");
    water = m;
  }
  const std::vector<int> soils = soil_material_indices(spec);
  if (water < 0 && soils.empty()) throw CaseError("materials", "the case needs a water or a soil material");
  // The hydrostatic start (particle_builder) measures depth along z: gravity must point down z.
  for (int a = 0; a + 1 < c.dimensions; ++a)
    if (a < spec.gravity_size() && spec.gravity(a) != 0.0)
      for (int b = 0; b < spec.bodies_size(); ++b)
        if (spec.bodies(b).initial().hydrostatic())
          throw CaseError("bodies[" + std::to_string(b) + "].initial.hydrostatic",
                          "a hydrostatic start needs gravity along -z only");
  // One ρ_w0 for the whole case: the water's, or 1000 kg/m³ in a soil-only case (every particle
  // has the mass ρ_w0 dp^dimensions, Section 3.2).
  c.water_density = reference_water_density(spec);
  if (water >= 0) {
    const auto& w = spec.materials(water).water();
    c.sound_speed = water_sound_speed(spec, water, particles);
    c.delta = w.has_delta() ? w.delta() : 0.1;
    c.viscosity_alpha = w.has_viscosity_alpha() ? w.viscosity_alpha() : 0.01;
  } else {
    c.sound_speed = 0.0;  // no free water
  }
  for (int m : soils) c.soils.push_back(soil_material(spec, m));
  c.forcing = spec.has_initialisation() ? initialisation_forcing(spec) : hydraulic_forcing(spec, 0.0);
  for (int b = 0; b < spec.bodies_size(); ++b)
    if (spec.bodies(b).kind() == v1::BOUNDARY && spec.bodies(b).has_pore_pressure())
      c.drained_walls.push_back({std::uint32_t(b), spec.bodies(b).pore_pressure()});
  c.cfl = spec.numerics().cfl() > 0 ? spec.numerics().cfl() : 0.2;
  c.max_dt = spec.numerics().max_dt();
  c.min_dt = spec.numerics().min_dt() > 0 ? spec.numerics().min_dt() : 1e-12;
  c.precision = precision;
  c.device = device;
  return c;
}

std::uint64_t run_initialisation(const v1::ScenarioSpec& spec, Engine& engine) {
  if (!spec.has_initialisation()) return 0;
  const std::uint64_t first = engine.step_count();
  engine.set_forcing(initialisation_forcing(spec));
  const double duration = spec.initialisation().duration();
  while (engine.time() < duration * (1 - 1e-12)) engine.step();
  engine.restart_clock();
  engine.set_forcing(hydraulic_forcing(spec, 0.0));
  return engine.step_count() - first;
}

}  // namespace cascade
