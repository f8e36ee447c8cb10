// The odd-even (checkerboard) mode of a particle field on its lattice (issue 13, item 5): at each
// soil particle, along each lattice axis where the particle has lattice neighbours at ±dp and
// ±2dp (each within dp/4 of the lattice site), the fourth difference
//   δ⁴p_i = p_{i−2} − 4 p_{i−1} + 6 p_i − 4 p_{i+1} + p_{i+2},
// and the mode's amplitude |δ⁴p_i| / 16: exactly A for a field that alternates by ±A from
// particle to particle, dp⁴ ∂⁴p/16 for a smooth one, 0 for a cubic. A fit of lower order (the
// linear fit of soil_profiles.h: pore_pressure_noise) reads a resolved curvature, h² ∂²p, as noise;
// the fourth difference is the usual detector of the odd-even mode on a grid, the quantity that
// Jameson, Schmidt & Turkel's (1981) fourth-difference dissipation acts on. It needs the particles
// near their lattice (a soil at rest or creeping); particles without a full stencil along any axis
// (corners, layers within 2dp of a surface along the normal) are not measured, and their count is
// reported.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "server/core/field_frame.h"
#include "server/core/types.h"
#include "tests/validation/validation_table.h"

namespace cascade::testing {

struct OddEvenMode {
  double largest = 0;         // the largest amplitude |δ⁴p|/16 over particles and axes (Pa)
  double where[3] = {0, 0, 0};  // the position of the particle where it is (frame coordinates)
  int axis = -1;                // and along which lattice axis (0: x, 1: the second, 2: z in 3D)
  double range = 0;           // max − min of the field over the soil (Pa)
  std::size_t measured = 0;   // soil particles with a full stencil along at least one axis
  std::size_t particles = 0;  // soil particles
};

inline OddEvenMode odd_even_mode(const FieldFrame& f, const std::string& field, double dp) {
  const auto* p = f.find(field);
  const int axes[3] = {0, f.dimensions == 2 ? 2 : 1, 2};  // 2D cases lie in the (x, z) plane
  std::vector<std::size_t> soil;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.phase[i] == std::uint8_t(Phase::soil)) soil.push_back(i);
  OddEvenMode out;
  out.particles = soil.size();
  if (soil.empty()) return out;
  // The particles by lattice site, relative to the first one.
  const auto site = [&](const double* x, int a) {
    return std::int64_t(std::llround((x[axes[a]] - f.position[3 * soil[0] + axes[a]]) / dp));
  };
  const auto key = [](std::int64_t a, std::int64_t b, std::int64_t c) {
    return (a * 2000003 + b) * 2000003 + c;
  };
  std::unordered_map<std::int64_t, std::vector<std::size_t>> sites;
  for (std::size_t i : soil) {
    const double* x = &f.position[3 * i];
    sites[key(site(x, 0), site(x, 1), f.dimensions == 3 ? site(x, 2) : 0)].push_back(i);
  }
  // The particle within dp/4 of x_i + k dp e_axis, or none.
  const auto neighbour = [&](std::size_t i, int axis, int k, std::size_t& found) {
    double target[3] = {f.position[3 * i], f.position[3 * i + 1], f.position[3 * i + 2]};
    target[axes[axis]] += k * dp;
    const auto it = sites.find(key(site(target, 0), site(target, 1), f.dimensions == 3 ? site(target, 2) : 0));
    if (it == sites.end()) return false;
    for (std::size_t j : it->second) {
      double r2 = 0;
      for (int c = 0; c < 3; ++c) r2 += (f.position[3 * j + c] - target[c]) * (f.position[3 * j + c] - target[c]);
      if (r2 < 0.0625 * dp * dp) return found = j, true;
    }
    return false;
  };
  double low = p->values[soil[0]], high = low;
  for (std::size_t i : soil) {
    low = std::min(low, p->values[i]), high = std::max(high, p->values[i]);
    bool measured = false;
    for (int axis = 0; axis < f.dimensions; ++axis) {
      std::size_t m2, m1, p1, p2;
      if (!neighbour(i, axis, -2, m2) || !neighbour(i, axis, -1, m1) || !neighbour(i, axis, 1, p1) ||
          !neighbour(i, axis, 2, p2))
        continue;
      const auto v = [&](std::size_t j) { return p->values[j]; };
      const double fourth = v(m2) - 4 * v(m1) + 6 * v(i) - 4 * v(p1) + v(p2);
      if (!(std::fabs(fourth) / 16 <= out.largest)) {  // larger, or NaN
        out.largest = std::fabs(fourth) / 16;
        for (int c = 0; c < 3; ++c) out.where[c] = f.position[3 * i + c];
        out.axis = axis;
      }
      measured = true;
    }
    out.measured += measured;
  }
  out.range = high - low;
  return out;
}

}  // namespace cascade::testing
