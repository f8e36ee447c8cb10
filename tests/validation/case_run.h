// Runs a case file through the same path as `cascade run` (loader → particle builder → engine, with
// the case's stages and rain series) for
// validation tests, without writing files. A case's initialisation stage runs in the constructor,
// as the runner runs it before t = 0.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "server/core/engine.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"
#include "server/scenario/rain_series.h"
#include "server/scenario/stage_setup.h"

namespace cascade::testing {

struct CaseRun {
  v1::ScenarioSpec spec;
  ParticleSet set;
  EngineConfig config;
  std::unique_ptr<Engine> engine;

  CaseRun(const std::string& case_file, const std::vector<std::string>& overrides = {},
          Precision precision = Precision::double_precision) {
    std::vector<CaseOverride> parsed;
    for (const auto& o : overrides) parsed.push_back(parse_override(o));
    spec = load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/" + case_file, parsed);
    set = build_particle_set(spec);
    config = engine_config(spec, set.particles, precision);
    engine = make_case_engine(spec, config, set.particles, &make_engine);
    initialisation_steps = run_initialisation(spec, *engine);
  }
  std::uint64_t initialisation_steps = 0;  // the case's initialisation stage, run by the constructor

  // One step, after the case's rain series (hydraulics.rainfall) has set the intensity due at the
  // engine's time, as the runner and the server apply it (server/scenario/rain_series.h).
  void step() {
    if (const auto due = CaseRain{}.due(spec, *engine)) {
      HydraulicForcing next = engine->forcing();
      next.rainfall_intensity = *due;
      engine->set_forcing(next);
    }
    engine->step();
  }
  void run_until(double t) {
    while (engine->time() < t) step();
  }
  void run_steps(std::uint64_t n) {
    for (std::uint64_t k = 0; k < n; ++k) step();
  }
};

// The water particles' field values of a frame, with their positions (frame coordinates x, y, z).
struct WaterSample {
  std::vector<double> x, y, z, value;
};

inline WaterSample water_values(const FieldFrame& frame, const std::string& field) {
  WaterSample s;
  const auto* f = frame.find(field);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.phase[i] != 0) continue;
    s.x.push_back(frame.position[3 * i]);
    s.y.push_back(frame.position[3 * i + 1]);
    s.z.push_back(frame.position[3 * i + 2]);
    s.value.push_back(f ? f->values[i * f->components] : 0.0);
  }
  return s;
}

}  // namespace cascade::testing
