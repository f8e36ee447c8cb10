// Wall time and memory of the implicit pore-water stage (server/quasistatic/implicit_pore_water.h)
// on a 3D slope under a storm: a wedge of sand (van Genuchten, K_sat 1e-5 m/s) on a drained base,
// dp = 0.1 m, rain of 20 mm/h, through the same stages a case runs (case file → StagedEngine).
//
//   build/release/bin/bench_pore_water [--length L] [--hours H] [--steps K]
//
// --length sets the wedge (L × L/2 × L/2 high, about L³/8 / dp³ soil particles: 20 m gives 10⁶);
// it runs K implicit steps, or the whole H hours when --steps is 0, and prints the particles, the
// time to build the engine and the stage (the fixed skeleton's network), the wall time per step
// and per simulated hour, the Picard iterations and the resident memory per soil particle.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "server/core/engine.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"
#include "server/scenario/stage_setup.h"
#include "server/solver/staged_engine.h"

namespace {

std::string slope_case(double length) {
  const std::string l = std::to_string(length), w = std::to_string(length / 2), h = std::to_string(length / 2);
  return "name: bench_slope_3d\ndimensions: 3\ndp: 0.1\nend_time: 30 day\n"
         "domain: {min: [0, 0, -0.4], max: [" + l + ", " + w + ", " + h + "]}\n"
         "gravity: [0, 0, -9.81]\n"
         "materials:\n"
         "  - name: sand\n"
         "    soil:\n"
         "      grain_density: 2650\n"
         "      porosity: 0.35\n"
         "      saturated_conductivity: 1e-5\n"
         "      water_bulk_modulus: 2e6\n"
         "      hydraulic: {van_genuchten: {s_min: 0.1, lambda: 0.5, p_ref: 4350}}\n"
         "      mechanical: {drucker_prager: {youngs_modulus: 2e7, poisson_ratio: 0.3, cohesion: 5e3,"
         " friction_angle: 34}}\n"
         "bodies:\n"
         "  - {name: base, kind: boundary, pore_pressure: 0, shape: {box: {min: [0, 0, -0.4], max: [" + l + ", " + w +
         ", 0]}}}\n"
         "  - name: wedge\n"
         "    kind: fluid\n"
         "    material: sand\n"
         "    shape: {extruded_polygon: {vertices: [[0, 0], [" + l + ", 0], [0, " + h + "]], y_min: 0, y_max: " + w +
         "}}\n"
         "    initial: {water_table: 0}\n"
         "hydraulics: {rainfall_intensity: 20 mm/h, ponding_pressure: 0}\n"
         "stages:\n"
         "  - pore_water: {initial_dt: 60 s, max_dt: 1 h}\n";
}

double resident_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024.0;  // the peak, which is what a machine must hold
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  double length = 6.0, hours = 24.0;
  long steps = 0;
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--length")) length = std::atof(argv[k + 1]);
    else if (!std::strcmp(argv[k], "--hours")) hours = std::atof(argv[k + 1]);
    else if (!std::strcmp(argv[k], "--steps")) steps = std::atol(argv[k + 1]);
    else return std::fprintf(stderr, "usage: bench_pore_water [--length L] [--hours H] [--steps K]\n"), 2;
  }
  const auto start = std::chrono::steady_clock::now();
  const auto spec = cascade::load_case_text(slope_case(length));
  const auto particles = cascade::build_particles(spec);
  const auto config = cascade::engine_config(spec, particles, cascade::Precision::double_precision);
  auto engine = cascade::make_case_engine(spec, config, particles, &cascade::make_engine);
  const double build = seconds_since(start);
  const double soil = double(particles.count(cascade::Phase::soil));
  const auto& staged = dynamic_cast<const cascade::StagedEngine&>(*engine);

  const auto stepping = std::chrono::steady_clock::now();
  long taken = 0;
  while ((steps > 0 && taken < steps) || (steps == 0 && engine->time() < hours * 3600.0)) {
    engine->step();
    ++taken;
  }
  const double wall = seconds_since(stepping);
  const double simulated = engine->time();
  std::printf("soil particles %.0f (%zu in all); engine and stage built in %.2f s\n", soil, particles.size(), build);
  std::printf("%ld implicit steps to t = %.3f h: %.3f s wall per step, %.2f s wall per simulated hour; "
              "mean step %.0f s\n",
              taken, simulated / 3600.0, wall / double(taken), wall / (simulated / 3600.0), simulated / double(taken));
  std::printf("peak resident memory %.0f MB, %.0f bytes per soil particle (engine, stage and solver)\n",
              resident_bytes() / 1e6, resident_bytes() / soil);
  const cascade::WaterBalance b = staged.water_balance();
  std::printf("water balance: rain %.6g m^3, storage %.6g, base %.6g, error %.2e of the rain\n", b.rain, b.storage,
              b.walls, b.error() / b.rain);
  return 0;
}
