// The case's rain (HydraulicBoundary: its rainfall series or constant intensity) as the runner, a
// replay and the server all apply it, with the operator's steering, so that a steered server run
// and its replay change the forcing at the same steps.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cascade/v1/journal.pb.h"
#include "cascade/v1/scenario.pb.h"
#include "server/core/engine.h"

namespace cascade {

// Who sets the rain intensity at a step boundary. The case does (its series; a constant is set
// once, by engine_config), until an operator steers: rainfall.intensity replaces the case's rain
// for the rest of the run; rainfall.factor returns to the case's rain, series or constant, times
// the factor (a forecast that doubles: factor 2), until the next steering.
class CaseRain {
 public:
  // An applied forcing change: the fields of its update mask and its new forcing.
  void steer(const std::vector<std::string>& mask, const v1::Forcing& forcing);
  // The intensity the case's rain asks for at `time` when it differs from `current`; nothing
  // while the intensity is steered, or for a constant rain without a factor.
  std::optional<double> due(const v1::ScenarioSpec& spec, double time, double current) const;
  std::optional<double> due(const v1::ScenarioSpec& spec, const Engine& engine) const {
    return due(spec, engine.time(), engine.forcing().rainfall_intensity);
  }
  std::optional<double> factor() const { return factor_; }

 private:
  bool steered_ = false;
  std::optional<double> factor_;
};

// " (hyetograph FILE)" when the case's series was read from a hyetograph file (rainfall_file),
// else empty: the runner's and the server's forcing events say where the series came from.
std::string rain_series_origin(const v1::ScenarioSpec& spec);

}  // namespace cascade
