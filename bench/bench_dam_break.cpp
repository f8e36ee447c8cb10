// Particle-steps per second and bytes per particle of the 3D dam break (cases/dam_break_3d.yaml)
// at several resolutions, float and double, 1 and 2 threads. Each benchmark builds the case,
// lets the flow start (20 steps untimed, 5 at the finest), then times whole Symplectic steps.
//
//   build/release/bin/bench_dam_break --benchmark_counters_tabular=true
//   build/release/bin/bench_dam_break --benchmark_filter='dp:0.0103'
//
// Counters: particles, particle_steps_per_second, bytes_per_particle (device memory of the
// particle and grid arrays over the particle count), steps.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <string>

#include "server/core/engine.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"

namespace {

using cascade::Precision;

void dam_break_3d(benchmark::State& state, double dp, Precision precision, int threads) {
  omp_set_num_threads(threads);
  const auto spec = cascade::load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/dam_break_3d.yaml",
                                            {cascade::parse_override("dp=" + std::to_string(dp))});
  const auto particles = cascade::build_particles(spec);
  const auto config = cascade::engine_config(spec, particles, precision);
  auto engine = cascade::make_engine(config, particles);
  for (int k = 0; k < (dp < 0.008 ? 5 : 20); ++k) engine->step();
  const std::uint64_t first = engine->step_count();
  for (auto _ : state) engine->step();
  const double steps = double(engine->step_count() - first);
  const double n = double(engine->particle_count());
  state.counters["particles"] = n;
  state.counters["steps"] = steps;
  state.counters["particle_steps_per_second"] = benchmark::Counter(n * steps, benchmark::Counter::kIsRate);
  state.counters["bytes_per_particle"] = double(engine->device_bytes()) / n;
  state.counters["water"] = double(particles.count(cascade::Phase::water));
  state.counters["sim_time_per_step"] = engine->time() / double(engine->step_count());
}

// dp giving about 1.4·10⁴, 0.9·10⁵, 2·10⁵ (the 0.0103 of the performance target) and 10⁶ particles
// in all, water and dummy particles.
void register_all() {
  for (double dp : {0.0315, 0.0145, 0.0103, 0.0054})
    for (Precision p : {Precision::single_precision, Precision::double_precision})
      for (int threads : {1, 2}) {
        const std::string name = std::string("DamBreak3D/dp:") + std::to_string(dp).substr(0, 6) +
                                 (p == Precision::single_precision ? "/float" : "/double") +
                                 "/threads:" + std::to_string(threads);
        benchmark::RegisterBenchmark(name.c_str(), dam_break_3d, dp, p, threads)
            ->Unit(benchmark::kMillisecond)
            ->MinTime(dp < 0.008 ? 10.0 : 5.0)
            ->UseRealTime();
      }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
