// PNG encoding with libpng: 8-bit RGB, zlib level 3 (a third of level 6's time on 1280×720
// snapshots for a few per cent more bytes).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "render/rgb_image.h"

namespace cascade::render {

std::vector<std::uint8_t> encode_png(const RgbImage& image);  // throws RenderError
void write_png(const std::filesystem::path& path, const RgbImage& image);

}  // namespace cascade::render
