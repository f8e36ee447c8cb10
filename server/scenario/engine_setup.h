// ScenarioSpec + initial particles → the engine's constants (EngineConfig). The headless runner and
// the server both start an engine through this one function.
#pragma once

#include "cascade/v1/scenario.pb.h"
#include "server/core/engine.h"
#include "server/core/host_particles.h"

namespace cascade {

// Fills every constant of the engine from the spec (defaults applied) and the particles (the
// sound speed of Eq. 24a depends on the water's height): ρ_w0 of the case (the water's, 1000 in a
// soil-only case), the water constants (c_w0 = 0 without a water material), one SoilMaterial per
// soil material in spec order (soil_setup.h), the drained walls (Body.pore_pressure) and the
// hydraulic forcing at the start: the initialisation stage's when the case has one, else the
// case's own at t = 0. Throws CaseError
// naming the key when the spec has neither a water nor a soil material, or two water materials.
EngineConfig engine_config(const v1::ScenarioSpec& spec, const HostParticles& particles, Precision precision,
                           Device device = Device::cpu);

// The initialisation stage of the case (ScenarioSpec.initialisation), on an engine started from
// engine_config: steps under the stage's conditions until its duration is reached (the last step
// is not shortened: the stage may run past it by less than one step), then sets the clock back to
// t = 0 with the displacement measured from there (Engine::restart_clock) and hands the engine the
// case's own forcing at t = 0. Does nothing for a case without one. Returns the steps it took.
std::uint64_t run_initialisation(const v1::ScenarioSpec& spec, Engine& engine);

}  // namespace cascade
