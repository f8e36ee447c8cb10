// Write then read: libpng decodes what encode_png wrote, pixel for pixel.
#include <gtest/gtest.h>
#include <png.h>

#include "render/png_encoder.h"

namespace cascade::render {

TEST(PngEncoder, RoundTrip) {
  RgbImage image(37, 11);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) image.set(x, y, {std::uint8_t(7 * x), std::uint8_t(23 * y), std::uint8_t(x * y)});
  const std::vector<std::uint8_t> bytes = encode_png(image);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(png_sig_cmp(bytes.data(), 0, 8), 0);

  png_image decoded{};
  decoded.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_memory(&decoded, bytes.data(), bytes.size())) << decoded.message;
  EXPECT_EQ(decoded.width, 37u);
  EXPECT_EQ(decoded.height, 11u);
  decoded.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(decoded));
  ASSERT_TRUE(png_image_finish_read(&decoded, nullptr, pixels.data(), 0, nullptr)) << decoded.message;
  EXPECT_EQ(pixels, image.pixels);
}

}  // namespace cascade::render
