// A 5×7 bitmap font of our own for the labels drawn into snapshots: printable ASCII letters,
// digits and the signs that numbers, units and field names use. Others draw as '?'.
#pragma once

#include <array>
#include <cstdint>

namespace cascade::render {

inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = 6;  // one blank column between letters

// Seven rows, top first; bit 4 of a row is its leftmost pixel.
using Glyph = std::array<std::uint8_t, kGlyphHeight>;

const Glyph& glyph(char c);

}  // namespace cascade::render
