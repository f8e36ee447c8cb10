// What is drawn over the particles: the colour bar (field name and units, the map from the range's
// minimum at the bottom to its maximum at the top, five labels beside it) in a panel on the right,
// and the simulated time at the top left. Drawn into the read-back image, so the pixels are exact.
#pragma once

#include <string>
#include <vector>

#include "render/colour_map.h"
#include "render/rgb_image.h"

namespace cascade::render {

struct ColourBarLayout {
  int scene_width;      // the particles are drawn in columns [0, scene_width)
  int bar_x, bar_top, bar_width, bar_height;  // bar_top: the row of the range's maximum
  int label_x;          // left edge of the tick labels
  int text_scale;       // font pixels per image pixel
};

// Font pixels per image pixel: 1 below 720 rows, then one more per 360 rows (2 at 720, 6 at 2160).
int text_scale(int height);
ColourBarLayout colour_bar_layout(int width, int height);

// The five tick labels, bottom first ("%.3g").
std::vector<std::string> colour_bar_labels(double min, double max);

// A colour that reads on `background`: black on light, white on dark.
Rgb8 text_colour(Rgb8 background);

void draw_colour_bar(RgbImage& image, const ColourBarLayout& layout, const ColourMap& map, double min, double max,
                     const std::string& title, Rgb8 background);
void draw_time_label(RgbImage& image, double time, Rgb8 background);

}  // namespace cascade::render
