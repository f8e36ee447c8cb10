#include "server/scenario/rain_series.h"

#include "server/scenario/soil_setup.h"

namespace cascade {

void CaseRain::steer(const std::vector<std::string>& mask, const v1::Forcing& forcing) {
  for (const auto& field : mask) {
    if (field == "rainfall.intensity") steered_ = true, factor_.reset();
    if (field == "rainfall.factor") steered_ = false, factor_ = forcing.rainfall().factor();
  }
}

std::optional<double> CaseRain::due(const v1::ScenarioSpec& spec, double time, double current) const {
  if (steered_) return std::nullopt;
  if (!factor_ && spec.hydraulics().rainfall().empty()) return std::nullopt;  // constant: set by engine_config
  const double due = hydraulic_forcing(spec, time).rainfall_intensity * factor_.value_or(1.0);
  if (due == current) return std::nullopt;
  return due;
}

std::string rain_series_origin(const v1::ScenarioSpec& spec) {
  const std::string& file = spec.hydraulics().rainfall_file();
  return file.empty() ? std::string() : " (hyetograph " + file + ")";
}

}  // namespace cascade
