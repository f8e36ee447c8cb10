// Colour maps: scalar in [0, 1] → sRGB. Viridis (perceptually uniform, sequential) for fields
// with one sign; Moreland's cool-warm (diverging) for signed fields such as pore pressure, whose
// zero is the white midpoint; fixed colours per phase.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace cascade::render {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb8& o) const { return r == o.r && g == o.g && b == o.b; }
};

enum class ColourMapKind { viridis, cool_warm };

// A 256-entry table, built once from the map's definition.
class ColourMap {
 public:
  static const ColourMap& get(ColourMapKind kind);

  // t is clamped to [0, 1]; NaN maps to 0.
  Rgb8 at(double t) const;
  const std::array<Rgb8, 256>& table() const { return table_; }
  ColourMapKind kind() const { return kind_; }

 private:
  explicit ColourMap(ColourMapKind kind);
  ColourMapKind kind_;
  std::array<Rgb8, 256> table_;
};

std::string colour_map_name(ColourMapKind kind);

// The fixed colours of water, soil and boundary particles (FieldFrame::phase 0, 1, 2).
Rgb8 phase_colour(std::uint8_t phase);

}  // namespace cascade::render
