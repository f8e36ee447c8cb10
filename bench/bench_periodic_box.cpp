// Cost per particle-step at a fixed particle mix: a fully periodic 3D box of water (no walls, no
// gravity) with a random velocity field, h = 1.732 dp as in the dam break, from 10⁴ to 10⁷
// particles. Every particle is a water particle with a full neighbourhood, so the cost per
// particle-step should not depend on N; the dam break's changes with its mix of water and dummy
// particles (docs/performance.md).
//
//   build/release/bin/bench_periodic_box --benchmark_counters_tabular=true --benchmark_filter='particles:(10648|103823|1000000)/'
//   build/release/bin/bench_periodic_box --benchmark_counters_tabular=true --benchmark_filter='particles:(1000000|9938375)/float'
//
// The 10⁷ box took 12.7 GiB at its peak in float (1177 bytes per particle and the set-up's host
// arrays) and 22 s per step on two cores, 16 minutes for the second command (2026-12-07).
#include <cmath>
#include <random>
#include <string>

#include "bench/engine_bench.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"

namespace {

using cascade::Precision;

void periodic_box(benchmark::State& state, int side, Precision precision) {
  const double dp = 0.01;
  const std::string length = std::to_string(side * dp);
  const std::string yaml = "name: periodic_box\ndimensions: 3\ndp: 0.01\nh_over_dp: 1.732\nend_time: 1.0\n"
                           "domain: {min: [0, 0, 0], max: [" + length + ", " + length + ", " + length +
                           "], periodic: [true, true, true]}\ngravity: [0, 0, 0]\n"
                           "materials:\n  - {name: water, water: {density: 1000, sound_speed: 20}}\n"
                           "bodies:\n  - {name: water, kind: fluid, material: water, shape: {box: {min: [0, 0, 0], "
                           "max: [" + length + ", " + length + ", " + length + "]}}}\n";
  const auto spec = cascade::load_case_text(yaml);
  auto particles = cascade::build_particles(spec);
  std::mt19937 rng(7);
  std::normal_distribution<double> speed(0.0, 0.5);  // a stirred box: the lists are rebuilt
  for (double& v : particles.velocity) v = speed(rng);
  const auto config = cascade::engine_config(spec, particles, precision);
  auto engine = cascade::make_engine(config, particles);
  cascade::bench::time_steps(state, *engine, 5);
}

}  // namespace

// 22³ ≈ 1.1·10⁴, 47³ ≈ 1.0·10⁵, 100³ = 10⁶, 215³ ≈ 9.9·10⁶ particles.
int main(int argc, char** argv) {
  cascade::bench::register_sizes<int>(
      "PeriodicBox3D", {22, 47, 100, 215}, [](const int& side) { return "particles:" + std::to_string(side * side * side); },
      2, 3.0, periodic_box);
  return cascade::bench::run_benchmarks(argc, argv);
}
