// The case's rain series (HydraulicBoundary.rainfall) as the runner and the server both apply it,
// so that a steered server run and its replay change the forcing at the same steps.
#pragma once

#include <optional>
#include <string>

#include "cascade/v1/scenario.pb.h"
#include "server/core/engine.h"

namespace cascade {

// At a step boundary: the intensity the series asks for at the engine's time when it differs from
// the engine's; nothing for a case without a series. A caller that has steered the intensity stops
// asking: the steered value replaces the series for the rest of the run.
std::optional<double> due_rain_change(const v1::ScenarioSpec& spec, const Engine& engine);

// " (hyetograph FILE)" when the case's series was read from a hyetograph file (rainfall_file),
// else empty: the runner's and the server's forcing events say where the series came from.
std::string rain_series_origin(const v1::ScenarioSpec& spec);

}  // namespace cascade
