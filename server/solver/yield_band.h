// The pore-water stage's end criterion (StageEnd.yield_band in scenario.proto): has yield spread
// far enough through the soil for the slope to fail? Measured on a frame, from its yield_ratio
// field (drucker_prager.h: the shear stress over the shear strength at the same mean stress).
#pragma once

#include <cstddef>
#include <string>

#include "server/core/field_frame.h"

namespace cascade {

struct YieldBandCriterion {
  double ratio = 1.0;      // a soil particle counts as yielded at yield_ratio >= ratio
  double volume = 0;       // > 0: the yielded volume (m^d, dp^d per particle) exceeds it
  bool connected = false;  // a connected set of yielded particles meets the free surface at points `span` apart
  double span = 0;         // m
  bool active() const { return volume > 0 || connected; }
};

struct YieldBandMeasure {
  std::size_t yielded = 0;     // soil particles at or above the ratio
  double volume = 0;           // their volume (m^d)
  double connected_span = 0;   // the largest extent (bounding-box diagonal) of the free-surface
                               // members of one connected yielded set (m): the band cuts the soil
                               // from surface to surface over that span; particles within 1.5 dp
                               // connect
};

YieldBandMeasure measure_yield_band(const FieldFrame& frame, const YieldBandCriterion& criterion, double dp);

// The reason the criterion holds ("yielded volume 3.2 m² > 3 m²"), or empty while it does not.
std::string yield_band_reached(const YieldBandMeasure& measure, const YieldBandCriterion& criterion);

}  // namespace cascade
