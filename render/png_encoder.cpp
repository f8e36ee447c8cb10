#include "render/png_encoder.h"

#include <png.h>

#include <fstream>
#include <memory>
#include <string>

#include "render/egl_context.h"

namespace cascade::render {

namespace {

void append(png_structp png, png_bytep data, png_size_t size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + size);
}

}  // namespace

std::vector<std::uint8_t> encode_png(const RgbImage& image) {
  // On the heap: after libpng's longjmp only what was not changed since setjmp may be read.
  auto out = std::make_unique<std::vector<std::uint8_t>>();
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw RenderError("libpng: cannot create a write structure");
  }
  // libpng reports errors by longjmp to here; nothing with a destructor is created in between.
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw RenderError("libpng failed to encode a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                      " image");
  }
  out->reserve(image.pixels.size() / 4);
  png_set_write_fn(png, out.get(), append, nullptr);
  png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 3);
  png_write_info(png, info);
  for (int row = 0; row < image.height; ++row)
    png_write_row(png, &image.pixels[std::size_t(row) * std::size_t(image.width) * 3]);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::move(*out);
}

void write_png(const std::filesystem::path& path, const RgbImage& image) {
  const std::vector<std::uint8_t> bytes = encode_png(image);
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!file) throw RenderError("cannot write " + path.string());
}

}  // namespace cascade::render
