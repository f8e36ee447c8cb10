// What every engine benchmark shares: timing whole steps of a built case and reporting
// particle-steps per second and bytes per particle, and the registration of one benchmark per
// size, precision and thread count.
#pragma once

#include <benchmark/benchmark.h>
#include <omp.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "server/core/engine.h"

namespace cascade::bench {

// Steps `warm_up` steps untimed, then times whole steps. Counters: particles, steps,
// particle_steps_per_second (every particle, water, soil and dummy), bytes_per_particle (the
// engine's particle, grid and neighbour-list arrays over the particle count).
inline void time_steps(benchmark::State& state, Engine& engine, int warm_up) {
  for (int k = 0; k < warm_up; ++k) engine.step();
  const std::uint64_t first = engine.step_count();
  for (auto _ : state) engine.step();
  const double steps = double(engine.step_count() - first);
  const double n = double(engine.particle_count());
  state.counters["particles"] = n;
  state.counters["steps"] = steps;
  state.counters["particle_steps_per_second"] = benchmark::Counter(n * steps, benchmark::Counter::kIsRate);
  state.counters["bytes_per_particle"] = double(engine.device_bytes()) / n;
}

// Registers `run(state, size, precision)` as `prefix/<label>/<float|double>/threads:<t>` for
// every size, both precisions and 1 and 2 threads, each for at least `seconds`; sizes from
// `long_from` on for 8 steps: the lists are rebuilt every few steps, and a time of one or two
// steps (all that 10 s holds at 10⁷ particles) may hold no rebuild.
template <typename Size>
void register_sizes(const std::string& prefix, const std::vector<Size>& sizes,
                    const std::function<std::string(const Size&)>& label, std::size_t long_from, double seconds,
                    const std::function<void(benchmark::State&, const Size&, Precision)>& run) {
  for (std::size_t k = 0; k < sizes.size(); ++k)
    for (Precision p : {Precision::single_precision, Precision::double_precision})
      for (int threads : {1, 2}) {
        const std::string name = prefix + "/" + label(sizes[k]) +
                                 (p == Precision::single_precision ? "/float" : "/double") +
                                 "/threads:" + std::to_string(threads);
        const Size size = sizes[k];
        auto* registered = benchmark::RegisterBenchmark(name.c_str(),
                                     [run, size, p, threads](benchmark::State& state) {
                                       omp_set_num_threads(threads);
                                       run(state, size, p);
                                     })
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
        if (k >= long_from) registered->Iterations(8);
        else registered->MinTime(seconds);
      }
}

inline int run_benchmarks(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace cascade::bench
