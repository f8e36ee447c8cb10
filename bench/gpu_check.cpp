// The CUDA engine against the CPU engine (scripts/gpu_check.sh; issue 14 item 13): the 2D
// hydrostatic tank, the 2D dam break and the Terzaghi soil column, each built once and run the same
// number of steps on both backends in the same precision. Prints, per case and field, the largest
// difference between the backends over the field's largest magnitude, the simulated times reached,
// and the particle-steps per second of each backend; exits 1 when a difference exceeds the
// tolerance, 2 when the build has no CUDA backend or a case fails to load.
//
// Both backends run the same kernels (one source, server/physics/); they may differ only by
// rounding: nvcc contracts multiply-adds and CUDA's sqrt, pow and exp round differently in the
// last place. The tolerance allows rounding differences grown over the steps; it is not derived
// from a measurement (no GPU run yet): the first run records what the backends really differ by.
//
// usage: gpu_check [--steps N] [--precision double|float]
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "server/core/engine.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"
#include "server/scenario/stage_setup.h"

namespace {

using namespace cascade;

struct Run {
  FieldFrame frame;
  double particle_steps_per_second = 0;
};

Run run(const v1::ScenarioSpec& spec, const HostParticles& particles, Precision precision, Device device,
        int steps) {
  const EngineConfig config = engine_config(spec, particles, precision, device);
  auto engine = make_case_engine(spec, config, particles, &make_engine);
  run_initialisation(spec, *engine);
  engine->step();  // untimed: first-touch allocations, CUDA context and kernel loading
  const auto start = std::chrono::steady_clock::now();
  for (int k = 1; k < steps; ++k) engine->step();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {engine->frame(), double(engine->particle_count()) * (steps - 1) / seconds};
}

// Largest |a − b| over the largest |a| of a field, particles matched by id.
double relative_difference(const std::vector<double>& a, const std::vector<double>& b, int components,
                           const std::vector<std::size_t>& b_index) {
  double largest = 0, scale = 0;
  for (std::size_t i = 0; i < b_index.size(); ++i)
    for (int c = 0; c < components; ++c) {
      const double x = a[i * components + c], y = b[b_index[i] * components + c];
      scale = std::max(scale, std::fabs(x));
      largest = std::max(largest, std::isfinite(x - y) ? std::fabs(x - y) : INFINITY);
    }
  return scale > 0 ? largest / scale : largest;
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 500;
  Precision precision = Precision::double_precision;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--steps") && k + 1 < argc) {
      steps = std::max(2, std::atoi(argv[++k]));
    } else if (!std::strcmp(argv[k], "--precision") && k + 1 < argc) {
      precision = std::strcmp(argv[++k], "float") == 0 ? Precision::single_precision : Precision::double_precision;
    } else {
      std::fprintf(stderr, "usage: gpu_check [--steps N] [--precision double|float]\n");
      return 2;
    }
  }
  // Rounding differences grown over the steps: a few hundred ulps of the field's scale in double,
  // the same relative growth from float's ulp (6e-8) in float.
  const double tolerance = precision == Precision::double_precision ? 1e-9 : 1e-3;
  bool all_within = true;
  for (const char* name : {"hydrostatic_tank_2d", "dam_break_2d", "terzaghi"}) {
    Run cpu, gpu;
    try {
      const auto spec = load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/" + name + ".yaml");
      const auto set = build_particle_set(spec);
      cpu = run(spec, set.particles, precision, Device::cpu, steps);
      gpu = run(spec, set.particles, precision, Device::cuda, steps);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gpu_check: %s: %s\n", name, e.what());
      return 2;
    }
    std::printf("%s, %s, %d steps: t = %.9g s (CPU, %d threads), %.9g s (CUDA); particle-steps/s: CPU %.3e, "
                "CUDA %.3e\n",
                name, precision == Precision::double_precision ? "double" : "float", steps, cpu.frame.time,
                omp_get_max_threads(), gpu.frame.time, cpu.particle_steps_per_second, gpu.particle_steps_per_second);
    std::unordered_map<std::uint32_t, std::size_t> gpu_index_of;
    for (std::size_t i = 0; i < gpu.frame.size(); ++i) gpu_index_of[gpu.frame.id[i]] = i;
    std::vector<std::size_t> match;
    for (const std::uint32_t id : cpu.frame.id) match.push_back(gpu_index_of.at(id));
    auto report = [&](const std::string& field, double difference) {
      const bool within = difference <= tolerance;
      all_within = all_within && within;
      std::printf("  %-24s %.3e %s\n", field.c_str(), difference, within ? "" : "ABOVE THE TOLERANCE");
    };
    report("position", relative_difference(cpu.frame.position, gpu.frame.position, 3, match));
    for (const auto& field : cpu.frame.fields)
      if (const auto* other = gpu.frame.find(field.name))
        report(field.name, relative_difference(field.values, other->values, field.components, match));
  }
  std::printf("gpu_check: tolerance %.0e of each field's largest magnitude: %s\n", tolerance,
              all_within ? "all within" : "SOME ABOVE");
  return all_within ? 0 : 1;
}
