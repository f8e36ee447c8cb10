#include "render/rgb_image.h"

#include "render/bitmap_font.h"

namespace cascade::render {

void draw_text(RgbImage& image, int x, int y, const std::string& text, int scale, Rgb8 colour) {
  for (char c : text) {
    const Glyph& g = glyph(c);
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col)
        if (g[std::size_t(row)] & (1u << (kGlyphWidth - 1 - col)))
          image.fill_rect(x + col * scale, y + row * scale, scale, scale, colour);
    x += kGlyphAdvance * scale;
  }
}

int text_width(const std::string& text, int scale) {
  return text.empty() ? 0 : (int(text.size()) * kGlyphAdvance - 1) * scale;
}

}  // namespace cascade::render
