// How far a split run's frame is from one process's (tests/parallel): the largest difference of
// the positions in units of dp, and of every field over that field's range in one process's frame.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "server/core/field_frame.h"

namespace cascade::testing {

struct FrameDifference {
  double position = 0;
  double field = 0;
  std::string worst_field;

  void widen(const FrameDifference& d) {
    position = std::max(position, d.position);
    if (d.field >= field) field = d.field, worst_field = d.worst_field;
  }
};

inline FrameDifference frame_difference(const FieldFrame& split, const FieldFrame& alone, double dp) {
  FrameDifference d;
  EXPECT_EQ(split.size(), alone.size());
  if (split.size() != alone.size()) return {1e300, 1e300, "particle count"};
  for (std::size_t i = 0; i < alone.position.size(); ++i)
    d.position = std::max(d.position, std::abs(split.position[i] - alone.position[i]) / dp);
  for (const auto& field : alone.fields) {
    const auto* other = split.find(field.name);
    if (!other) {
      ADD_FAILURE() << "the split run's frame has no field " << field.name;
      continue;
    }
    const auto [low, high] = std::minmax_element(field.values.begin(), field.values.end());
    const double range = field.values.empty() ? 0.0 : *high - *low;
    double worst = 0;
    for (std::size_t k = 0; k < field.values.size(); ++k) {
      const double delta = std::abs(other->values[k] - field.values[k]);
      worst = std::max(worst, range > 0 ? delta / range : (delta > 0 ? 1.0 : 0.0));
    }
    if (worst >= d.field) d.field = worst, d.worst_field = field.name;
  }
  return d;
}

}  // namespace cascade::testing
