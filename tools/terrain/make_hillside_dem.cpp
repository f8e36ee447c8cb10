// Writes the shipped terrain: the analytic hillside (hillside.h) as two GeoTIFFs, the ground
// surface and the bedrock, at 1 m pixels in EPSG:2326.
//   make_hillside_dem OUT_DIR   → OUT_DIR/hillside_surface.tif, OUT_DIR/hillside_bedrock.tif
#include <cstdio>
#include <string>
#include <vector>

#include "server/terrain/raster.h"
#include "tools/terrain/hillside.h"

namespace hs = cascade::hillside;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_hillside_dem OUT_DIR\n");
    return 2;
  }
  const int columns = int(hs::kWidth / hs::kPixel), rows = int(hs::kHeight / hs::kPixel);
  const double top = hs::kY0 + hs::kHeight;  // the first row is the northern one
  for (const auto& [name, height] : {std::pair{"hillside_surface.tif", &hs::surface}, {"hillside_bedrock.tif", &hs::bedrock}}) {
    std::vector<double> values;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < columns; ++c)  // the value at the pixel's centre
        values.push_back(height(hs::kX0 + (c + 0.5) * hs::kPixel, top - (r + 0.5) * hs::kPixel));
    const std::string path = std::string(argv[1]) + "/" + name;
    try {
      cascade::write_geotiff(path, columns, rows, hs::kX0, top, hs::kPixel, values, hs::kEpsg);
    } catch (const cascade::RasterError& e) {
      std::fprintf(stderr, "make_hillside_dem: %s\n", e.what());
      return 1;
    }
    std::printf("%s: %d x %d pixels\n", path.c_str(), columns, rows);
  }
  return 0;
}
