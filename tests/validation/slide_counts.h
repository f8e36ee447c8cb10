// What the landslide tests count on a frame: the water and soil particles still in the run (a
// particle the engine flagged `lost` keeps its phase in the frame, so it is counted apart: a
// count of all particles of a phase could never change), those outside the case's domain, and
// the soil's centroid with its speed (every particle has one mass, so counts are masses and means
// are centroids).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "cascade/v1/scenario.pb.h"
#include "server/core/field_frame.h"
#include "server/core/types.h"
#include "tests/validation/validation_table.h"

namespace cascade::testing {

struct PhaseCounts {
  std::size_t water = 0, soil = 0, outside = 0, lost = 0;
};

inline PhaseCounts count(const FieldFrame& f, const v1::ScenarioSpec& spec) {
  PhaseCounts n;
  const auto* lost = f.find("lost");
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double x = f.position[3 * i], z = f.position[3 * i + 2];
    const int vertical = spec.dimensions() - 1;  // the domain's z index
    const bool inside = x >= spec.domain().min(0) && x <= spec.domain().max(0) &&
                        z >= spec.domain().min(vertical) && z <= spec.domain().max(vertical) && std::isfinite(x) &&
                        std::isfinite(z);
    if (f.phase[i] != std::uint8_t(Phase::boundary) && !inside) ++n.outside;
    if (lost && lost->values[i] != 0) {
      ++n.lost;
      continue;
    }
    if (f.phase[i] == std::uint8_t(Phase::water)) ++n.water;
    if (f.phase[i] == std::uint8_t(Phase::soil)) ++n.soil;
  }
  return n;
}

// The four figures of "nothing lost" from the counts at the start and at `when` (e.g. "at the end"):
// each phase's count (its mass, every particle having one) unchanged, none outside the domain, none
// flagged lost.
inline void validate_nothing_lost(const std::string& case_name, const PhaseCounts& start, const PhaseCounts& end,
                                  const std::string& when) {
  const std::string conservation = "mass conservation: a particle's mass is fixed, so a phase's count is its mass";
  CASCADE_VALIDATE({.case_name = case_name, .reference = conservation,
                    .metric = "water particles gained or lost " + when + ", |N_end − N_start|",
                    .measured = std::abs(double(end.water) - double(start.water)), .reference_value = 0,
                    .bound = Bound::at_most, .tolerance_source = "exact"});
  CASCADE_VALIDATE({.case_name = case_name, .reference = conservation,
                    .metric = "soil particles gained or lost " + when + ", |N_end − N_start|",
                    .measured = std::abs(double(end.soil) - double(start.soil)), .reference_value = 0,
                    .bound = Bound::at_most, .tolerance_source = "exact"});
  CASCADE_VALIDATE({.case_name = case_name, .reference = "no particle leaves the domain",
                    .metric = "particles outside the domain " + when, .measured = double(end.outside),
                    .reference_value = 0, .bound = Bound::at_most, .tolerance_source = "exact"});
  CASCADE_VALIDATE({.case_name = case_name, .reference = "no particle leaves the domain",
                    .metric = "particles flagged lost " + when, .measured = double(end.lost), .reference_value = 0,
                    .bound = Bound::at_most, .tolerance_source = "exact"});
}

// The soil's centroid height and the speed of its centroid.
inline void soil_centroid(const FieldFrame& f, double* z, double* speed) {
  const auto* v = f.find("velocity");
  double zc = 0, vx = 0, vz = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.phase[i] != std::uint8_t(Phase::soil)) continue;
    zc += f.position[3 * i + 2], vx += v->values[3 * i], vz += v->values[3 * i + 2], ++n;
  }
  *z = zc / double(n);
  *speed = std::hypot(vx, vz) / double(n);
}

}  // namespace cascade::testing
