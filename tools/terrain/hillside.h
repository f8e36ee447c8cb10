// The analytic hillside behind the project's shipped terrain (cases/terrain/): a valley with a
// lake floor, a far bank, and a slope of up to 38° with a hollow in it whose colluvium is thicker,
// where landslides start. Map coordinates in the Hong Kong 1980 Grid (EPSG:2326), elevations in
// metres. make_hillside_dem writes it as GeoTIFFs; the terrain tests compare the case builder's
// particles with it.
#pragma once

#include <cmath>

namespace cascade::hillside {

constexpr int kEpsg = 2326;                     // Hong Kong 1980 Grid
constexpr double kX0 = 836000.0, kY0 = 818000.0;  // the rasters' north-west corner is (kX0, kY0 + kHeight)
constexpr double kWidth = 160.0, kHeight = 80.0;  // m, along X and Y
constexpr double kPixel = 1.0;                  // m

// 0 → 1 around `at` over about 3 `width`.
inline double rise(double t, double at, double width) { return 0.5 * (1.0 + std::tanh((t - at) / width)); }

// The hollow: 1 on its axis (Y = kY0 + 40) on the slope, fading across it and off the slope.
inline double hollow(double u, double v) {
  return std::exp(-std::pow((v - 40.0) / 10.0, 2)) * rise(u, 50.0, 8.0) * (1.0 - rise(u, 115.0, 8.0));
}

// The ground's elevation at map point (x, y).
inline double surface(double x, double y) {
  const double u = x - kX0, v = y - kY0;
  const double floor = 100.0 + 0.01 * v;
  const double far_bank = 4.0 * (1.0 - rise(u, 12.0, 3.0));
  const double hill = 26.0 * rise(u, 80.0, 17.0);  // steepest 26 / 34 = tan 37.4°
  const double gully = -1.5 * hollow(u, v);
  const double roughness = 0.15 * std::sin(0.31 * u + 0.7) * std::sin(0.23 * v + 0.3);
  return floor + far_bank + hill + gully + roughness;
}

// The soil's thickness: 1 m on the valley floor and the plateau, 2.2 m on the slope, 2.8 m in the
// hollow.
inline double thickness(double x, double y) {
  const double u = x - kX0, v = y - kY0;
  const double slope = rise(u, 55.0, 6.0) * (1.0 - rise(u, 110.0, 6.0));
  return 1.0 + 1.2 * slope + 0.6 * hollow(u, v);
}

inline double bedrock(double x, double y) { return surface(x, y) - thickness(x, y); }

// A house at the slope's toe, on the hollow's axis just above the lake's shore (elevation
// 101–104 m there), in the slide's path: an L-shaped block (a 8 m × 6 m hall and a 4 m × 6 m
// wing), founded down into the bedrock and roofed flat at 108 m. Its outline in map coordinates,
// counter-clockwise seen from above, and its plan split into triangles of outline indices.
// Whole metres, exact in the STL's float32.
constexpr double kHouseOutline[6][2] = {{kX0 + 58, kY0 + 34}, {kX0 + 66, kY0 + 34}, {kX0 + 66, kY0 + 40},
                                        {kX0 + 62, kY0 + 40}, {kX0 + 62, kY0 + 46}, {kX0 + 58, kY0 + 46}};
constexpr int kHousePlan[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 5}, {5, 3, 4}};
constexpr double kHouseBase = 96.0, kHouseRoof = 108.0;  // m

}  // namespace cascade::hillside
