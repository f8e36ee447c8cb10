// An 8-bit RGB image, top row first, and the 2D drawing the overlays need.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/colour_map.h"

namespace cascade::render {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // width × height × 3

  RgbImage() = default;
  RgbImage(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h) * 3, 0) {}

  Rgb8 at(int x, int y) const {
    const std::uint8_t* p = &pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
    return {p[0], p[1], p[2]};
  }
  void set(int x, int y, Rgb8 c) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::uint8_t* p = &pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }
  void fill_rect(int x, int y, int w, int h, Rgb8 c) {
    for (int j = y; j < y + h; ++j)
      for (int i = x; i < x + w; ++i) set(i, j, c);
  }
};

// Draws `text` with its top left corner at (x, y), each font pixel `scale` pixels wide.
void draw_text(RgbImage& image, int x, int y, const std::string& text, int scale, Rgb8 colour);
int text_width(const std::string& text, int scale);

}  // namespace cascade::render
