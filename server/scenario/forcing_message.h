// HydraulicForcing (the engine's free-surface conditions) ↔ cascade.v1.Forcing (the API's and the
// journal's), and the field-mask update that steering applies.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "cascade/v1/journal.pb.h"
#include "server/core/hydraulic_forcing.h"

namespace cascade {

// The field paths an update mask may name. rainfall.factor is not the engine's: CaseRain
// (rain_series.h) turns it into the intensity.
inline const std::array<const char*, 5> kSteerableForcingFields = {"rainfall.intensity", "rainfall.factor",
                                                                   "rainfall.region", "ponding.p_max", "ponding.p_min"};

v1::Forcing forcing_message(const HydraulicForcing& forcing, int dimensions);

// `current` with the fields named in `mask` taken from `update` (paths of kSteerableForcingFields,
// already validated): rainfall.region unset in `update` removes the region, ponding.p_min unset
// removes the drying limit. The other fields of `current` are kept.
HydraulicForcing updated_forcing(HydraulicForcing current, const v1::Forcing& update,
                                 const std::vector<std::string>& mask, int dimensions);

}  // namespace cascade
