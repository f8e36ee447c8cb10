#include "server/scenario/forcing_message.h"

#include <cmath>

namespace cascade {

v1::Forcing forcing_message(const HydraulicForcing& forcing, int dimensions) {
  v1::Forcing m;
  m.mutable_rainfall()->set_intensity(forcing.rainfall_intensity);
  if (forcing.has_region) {
    auto* region = m.mutable_rainfall()->mutable_region();
    for (int a = 0; a < dimensions; ++a) {
      region->add_min(forcing.region_min[a]);
      region->add_max(forcing.region_max[a]);
    }
  }
  m.mutable_ponding()->set_p_max(forcing.ponding_pressure);
  if (std::isfinite(forcing.drying_pressure)) m.mutable_ponding()->set_p_min(forcing.drying_pressure);
  return m;
}

HydraulicForcing updated_forcing(HydraulicForcing current, const v1::Forcing& update,
                                 const std::vector<std::string>& mask, int dimensions) {
  for (const auto& path : mask) {
    if (path == "rainfall.intensity") {
      current.rainfall_intensity = update.rainfall().intensity();
    } else if (path == "rainfall.region") {
      current.has_region = update.rainfall().has_region();
      for (int a = 0; a < 3; ++a) {
        const bool set = current.has_region && a < dimensions;
        current.region_min[a] = set ? update.rainfall().region().min(a) : 0.0;
        current.region_max[a] = set ? update.rainfall().region().max(a) : 0.0;
      }
    } else if (path == "ponding.p_max") {
      current.ponding_pressure = update.ponding().p_max();
    } else if (path == "ponding.p_min") {
      current.drying_pressure = update.ponding().has_p_min() ? update.ponding().p_min()
                                                             : HydraulicForcing{}.drying_pressure;
    }
  }
  return current;
}

}  // namespace cascade
