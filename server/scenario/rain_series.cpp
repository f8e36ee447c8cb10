#include "server/scenario/rain_series.h"

#include "server/scenario/soil_setup.h"

namespace cascade {

std::optional<double> due_rain_change(const v1::ScenarioSpec& spec, const Engine& engine) {
  if (spec.hydraulics().rainfall().empty()) return std::nullopt;  // constant: set once, by engine_config
  const double due = hydraulic_forcing(spec, engine.time()).rainfall_intensity;
  if (due == engine.forcing().rainfall_intensity) return std::nullopt;
  return due;
}

std::string rain_series_origin(const v1::ScenarioSpec& spec) {
  const std::string& file = spec.hydraulics().rainfall_file();
  return file.empty() ? std::string() : " (hyetograph " + file + ")";
}

}  // namespace cascade
