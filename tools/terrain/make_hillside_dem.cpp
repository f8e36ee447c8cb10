// Writes the shipped terrain: the analytic hillside (hillside.h) as two GeoTIFFs, the ground
// surface and the bedrock, at 1 m pixels in EPSG:2326, and the house at its toe as an ASCII STL in
// the same map coordinates.
//   make_hillside_dem OUT_DIR   → OUT_DIR/hillside_surface.tif, OUT_DIR/hillside_bedrock.tif,
//                                 OUT_DIR/toe_house.stl
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "server/terrain/raster.h"
#include "tools/terrain/hillside.h"

namespace hs = cascade::hillside;

namespace {

using Point = std::array<double, 3>;

void facet(std::ofstream& out, const Point& a, const Point& b, const Point& c) {
  const Point u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  Point n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  double length = 0;
  for (double x : n) length += x * x;
  for (double& x : n) x /= std::sqrt(length);
  out << "  facet normal " << n[0] << " " << n[1] << " " << n[2] << "\n    outer loop\n";
  for (const Point* p : {&a, &b, &c}) out << "      vertex " << (*p)[0] << " " << (*p)[1] << " " << (*p)[2] << "\n";
  out << "    endloop\n  endfacet\n";
}

// The house (hillside.h) as a closed STL surface, its triangles counter-clockwise seen from
// outside: the roof and the floor as the plan's triangles, two triangles per wall.
void write_house(const std::string& path) {
  std::ofstream out(path);
  out.precision(10);
  out << "solid toe_house\n";
  const auto corner = [](int k, double z) { return Point{hs::kHouseOutline[k][0], hs::kHouseOutline[k][1], z}; };
  for (const auto& t : hs::kHousePlan) {
    facet(out, corner(t[0], hs::kHouseRoof), corner(t[1], hs::kHouseRoof), corner(t[2], hs::kHouseRoof));
    facet(out, corner(t[0], hs::kHouseBase), corner(t[2], hs::kHouseBase), corner(t[1], hs::kHouseBase));
  }
  for (int k = 0; k < 6; ++k) {
    const int next = (k + 1) % 6;
    facet(out, corner(k, hs::kHouseBase), corner(next, hs::kHouseBase), corner(next, hs::kHouseRoof));
    facet(out, corner(k, hs::kHouseBase), corner(next, hs::kHouseRoof), corner(k, hs::kHouseRoof));
  }
  out << "endsolid toe_house\n";
}

}  // namespace

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
  const std::string house = std::string(argv[1]) + "/toe_house.stl";
  write_house(house);
  std::printf("%s: %zu triangles\n", house.c_str(), 2 * std::size(hs::kHousePlan) + 12);
  return 0;
}
