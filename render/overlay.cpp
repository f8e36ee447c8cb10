#include "render/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/bitmap_font.h"

namespace cascade::render {

namespace {

std::string format_g(const char* format, double v) {
  char text[48];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

constexpr int kLabelChars = 9;  // "-1.23e+05"

}  // namespace

int text_scale(int height) { return std::max(1, height / 360); }

ColourBarLayout colour_bar_layout(int width, int height) {
  ColourBarLayout l;
  l.text_scale = text_scale(height);
  const int s = l.text_scale, margin = 8 * s;
  l.bar_width = 12 * s;
  const int label_width = text_width(std::string(kLabelChars, '0'), s);
  l.scene_width = std::max(1, width - (margin + l.bar_width + 4 * s + label_width + margin));
  l.bar_x = l.scene_width + margin;
  l.label_x = l.bar_x + l.bar_width + 4 * s;
  l.bar_top = margin + 2 * (kGlyphHeight + 3) * s;  // below the title's two lines
  l.bar_height = std::max(2, height - l.bar_top - margin - kGlyphHeight * s);
  return l;
}

std::vector<std::string> colour_bar_labels(double min, double max) {
  std::vector<std::string> labels;
  for (int k = 0; k <= 4; ++k) {
    double v = min + (max - min) * k / 4.0;
    if (std::fabs(v) < 1e-12 * std::max(std::fabs(min), std::fabs(max))) v = 0;  // no "-2.3e-17" at the middle
    labels.push_back(format_g("%.3g", v));
  }
  return labels;
}

Rgb8 text_colour(Rgb8 background) {
  const double luminance = 0.2126 * background.r + 0.7152 * background.g + 0.0722 * background.b;
  return luminance > 128 ? Rgb8{0, 0, 0} : Rgb8{255, 255, 255};
}

void draw_colour_bar(RgbImage& image, const ColourBarLayout& l, const ColourMap& map, double min, double max,
                     const std::string& title, Rgb8 background) {
  const int s = l.text_scale;
  const Rgb8 ink = text_colour(background);
  // The title over two lines when it is wider than the panel: field name, then units.
  const auto split = title.find(" [");
  const std::vector<std::string> lines = split == std::string::npos || text_width(title, s) <= image.width - l.bar_x
                                             ? std::vector<std::string>{title}
                                             : std::vector<std::string>{title.substr(0, split), title.substr(split + 1)};
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int x = std::max(0, std::min(l.bar_x, image.width - 4 * s - text_width(lines[k], s)));
    draw_text(image, x, 8 * s + int(k) * (kGlyphHeight + 3) * s, lines[k], s, ink);
  }
  for (int row = 0; row < l.bar_height; ++row) {
    const double t = l.bar_height > 1 ? 1.0 - double(row) / double(l.bar_height - 1) : 0.5;
    image.fill_rect(l.bar_x, l.bar_top + row, l.bar_width, 1, map.at(t));
  }
  const std::vector<std::string> labels = colour_bar_labels(min, max);
  for (int k = 0; k <= 4; ++k) {
    const int row = l.bar_top + (l.bar_height - 1) * (4 - k) / 4;
    draw_text(image, l.label_x, row - kGlyphHeight * s / 2, labels[std::size_t(k)], s, ink);
  }
}

void draw_time_label(RgbImage& image, double time, Rgb8 background) {
  const int s = text_scale(image.height);
  draw_text(image, 8 * s, 8 * s, "t = " + format_g("%.6g", time) + " s", s, text_colour(background));
}

}  // namespace cascade::render
