// Particle-steps per second and bytes per particle of the 3D dam break (cases/dam_break_3d.yaml)
// at several resolutions, float and double, 1 and 2 threads. Each benchmark builds the case,
// lets the flow start (20 steps untimed, 5 at the finest), then times whole Symplectic steps.
//
//   build/release/bin/bench_dam_break --benchmark_counters_tabular=true
//   build/release/bin/bench_dam_break --benchmark_filter='dp:0.0103'
//
// Counters: particles, particle_steps_per_second, bytes_per_particle (device memory of the
// particle and grid arrays over the particle count), steps.
#include <cmath>
#include <string>

#include "bench/engine_bench.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"

namespace {

using cascade::Precision;

void dam_break_3d(benchmark::State& state, double dp, Precision precision) {
  const auto spec = cascade::load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/dam_break_3d.yaml",
                                            {cascade::parse_override("dp=" + std::to_string(dp))});
  const auto particles = cascade::build_particles(spec);
  const auto config = cascade::engine_config(spec, particles, precision);
  auto engine = cascade::make_engine(config, particles);
  cascade::bench::time_steps(state, *engine, dp < 0.008 ? 5 : 20);
  state.counters["water"] = double(particles.count(cascade::Phase::water));
  state.counters["sim_time_per_step"] = engine->time() / double(engine->step_count());
}

}  // namespace

// dp giving about 1.4·10⁴, 0.9·10⁵, 2·10⁵ (the 0.0103 of the performance target) and 10⁶ particles
// in all, water and dummy particles.
int main(int argc, char** argv) {
  cascade::bench::register_sizes<double>(
      "DamBreak3D", {0.0315, 0.0145, 0.0103, 0.0054},
      [](const double& dp) { return "dp:" + std::to_string(dp).substr(0, 6); }, 3, 5.0, dam_break_3d);
  return cascade::bench::run_benchmarks(argc, argv);
}
