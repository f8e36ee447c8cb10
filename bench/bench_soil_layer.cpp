// Particle-steps per second and bytes per particle of a soil-water case: a deforming, saturated,
// linear-elastic soil layer on an impermeable wall, periodic in x, at geostatic stress and
// hydrostatic pore pressure (every soil and pore-water term of a step runs: free surface, pore
// state, the walls' soil side, renormalised gradients, seepage, soil interaction, stress update),
// 2D at h = 1.5 dp, from 10⁴ to 10⁶ soil particles.
//
//   build/release/bin/bench_soil_layer --benchmark_counters_tabular=true
#include <string>
#include <utility>

#include "bench/engine_bench.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"

namespace {

using cascade::Precision;

// A layer `columns` × `layers` particles of dp = 0.01 m.
std::string layer_case(int columns, int layers) {
  const std::string width = std::to_string(columns * 0.01), height = std::to_string(layers * 0.01);
  return "name: soil_layer\ndimensions: 2\ndp: 0.01\nh_over_dp: 1.5\nend_time: 1.0\n"
         "domain: {min: [0, -0.05], max: [" + width + ", " + height + "], periodic: [true, false]}\n"
         "gravity: [0, -9.81]\n"
         "materials:\n"
         "  - name: sand\n"
         "    soil:\n"
         "      grain_density: 2000\n"
         "      porosity: 0.4\n"
         "      saturated_conductivity: 1e-5\n"
         "      water_bulk_modulus: 2e6\n"
         "      hydraulic: {gardner: {s_min: 0.2, alpha: 2.0}}\n"
         "      mechanical: {linear_elastic: {youngs_modulus: 1e7, poisson_ratio: 0.3}}\n"
         "bodies:\n"
         "  - {name: base, kind: boundary, shape: {box: {min: [0, -0.05], max: [" + width + ", 0]}}}\n"
         "  - name: layer\n"
         "    kind: fluid\n"
         "    material: sand\n"
         "    shape: {box: {min: [0, 0], max: [" + width + ", " + height + "]}}\n"
         "    initial: {water_table: " + height + "}\n";
}

void soil_layer(benchmark::State& state, const std::pair<int, int>& size, Precision precision) {
  const auto spec = cascade::load_case_text(layer_case(size.first, size.second));
  const auto particles = cascade::build_particles(spec);
  const auto config = cascade::engine_config(spec, particles, precision);
  auto engine = cascade::make_engine(config, particles);
  cascade::bench::time_steps(state, *engine, 5);
  state.counters["soil"] = double(particles.count(cascade::Phase::soil));
}

}  // namespace

// 100 × 100, 400 × 250 and 1000 × 1000 soil particles.
int main(int argc, char** argv) {
  cascade::bench::register_sizes<std::pair<int, int>>(
      "SoilLayer2D", {{100, 100}, {400, 250}, {1000, 1000}},
      [](const std::pair<int, int>& s) { return "soil:" + std::to_string(s.first * s.second); }, 2, 3.0, soil_layer);
  return cascade::bench::run_benchmarks(argc, argv);
}
