// Particle-steps per second and bytes per particle of the cascade cases: the 2D demo
// (cases/cascade_demo_2d.yaml, as the README's main job runs it) and a slice of the 3D cascade
// (cases/cascade_3d.yaml) about 10⁶ particles large, float and double, 1 and 2 threads. Each
// benchmark builds the case, steps untimed past the start, then times whole Symplectic steps of
// the rain on the unsaturated slope (the stage that takes most of a cascade's steps).
//
//   build/release/bin/bench_cascade --benchmark_counters_tabular=true
//   build/release/bin/bench_cascade --benchmark_filter='3d_slice/float/threads:2'
//
// Counters as bench_dam_break: particles, particle_steps_per_second, bytes_per_particle, steps;
// sim_time_per_step, the mean step (s).
#include <string>
#include <vector>

#include "bench/engine_bench.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"

namespace {

using cascade::Precision;

struct CascadeCase {
  std::string label;
  std::string file;
  std::vector<std::string> overrides;
  int warm_up;
};

// The 3D case cut to 32 m of its 45 m valley (y): the side wall, the slope (kept 21/45 of the
// length, centred) and the channel follow; about 1.0·10⁶ particles.
const std::vector<std::string> slice_3d = {
    "domain.max=[23.91, 32.3, 10.0]",
    "bodies[0].shape.extruded_polygon.y_max=32.3",
    "bodies[2].shape.box.min=[-0.3, 32.0, -0.3]",
    "bodies[2].shape.box.max=[23.91, 32.3, 8.6]",
    "bodies[3].shape.extruded_polygon.y_min=8.53",
    "bodies[3].shape.extruded_polygon.y_max=23.47",
    "bodies[4].shape.extruded_polygon.y_max=32.0",
};

void run_case(benchmark::State& state, const CascadeCase& c, Precision precision) {
  std::vector<cascade::CaseOverride> overrides;
  for (const auto& o : c.overrides) overrides.push_back(cascade::parse_override(o));
  const auto spec = cascade::load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/" + c.file, overrides);
  const auto particles = cascade::build_particles(spec);
  const auto config = cascade::engine_config(spec, particles, precision);
  auto engine = cascade::make_engine(config, particles);
  cascade::bench::time_steps(state, *engine, c.warm_up);
  state.counters["sim_time_per_step"] = engine->time() / double(engine->step_count());
}

}  // namespace

int main(int argc, char** argv) {
  cascade::bench::register_sizes<CascadeCase>(
      "Cascade",
      {{"demo_2d", "cascade_demo_2d.yaml", {}, 200}, {"3d_slice", "cascade_3d.yaml", slice_3d, 2}},
      [](const CascadeCase& c) { return c.label; }, 1, 5.0, run_case);
  return cascade::bench::run_benchmarks(argc, argv);
}
