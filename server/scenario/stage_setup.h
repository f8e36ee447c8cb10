// ScenarioSpec.stages → the engine that runs them (server/solver/staged_engine.h). The runner and
// the server both start a case's engine through make_case_engine, so a case's stages mean the same
// in a headless run, on the server and in a replay.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/core/engine.h"
#include "server/solver/staged_engine.h"

namespace cascade {

using EngineMaker = std::function<std::unique_ptr<Engine>(const EngineConfig&, const HostParticles&)>;

// The stages of the spec with their defaults applied ("0 means ..." of scenario.proto); a stage
// without a name takes its kind's (geostatic, pore_water, dynamic).
std::vector<StagePlan> stage_plans(const v1::ScenarioSpec& spec);

// The output intervals (s) in force during a stage: the stage's own, else the case's
// (output.interval; output.probe_interval, else a tenth of the frame interval).
double stage_frame_interval(const v1::ScenarioSpec& spec, int stage);
double stage_probe_interval(const v1::ScenarioSpec& spec, int stage);

// The engine of the case: `make` (the dynamic engine) alone for a case without stages, else a
// StagedEngine around it.
std::unique_ptr<Engine> make_case_engine(const v1::ScenarioSpec& spec, const EngineConfig& config,
                                         const HostParticles& particles, const EngineMaker& make);

}  // namespace cascade
