// What the 1D soil-column tests share: the layer-averaged pore pressure of a frame, linear
// interpolation in a reference profile, and the reference Richards solver's soil made from the
// engine's material (the same curves and pore-water bulk modulus).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "server/core/field_frame.h"
#include "server/core/soil_material.h"
#include "server/core/types.h"
#include "tests/reference/richards_1d.h"

namespace cascade::testing {

// Layer-averaged pore pressure of the soil (layers of particles at equal z).
inline std::map<double, double> layer_pressures(const FieldFrame& f) {
  std::map<double, std::pair<double, int>> sums;
  const auto* p = f.find("pore_pressure");
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.phase[i] == std::uint8_t(Phase::soil)) {
      auto& s = sums[std::round(f.position[3 * i + 2] * 1e6) / 1e6];
      s.first += p->values[i];
      s.second += 1;
    }
  std::map<double, double> out;
  for (const auto& [z, s] : sums) out[z] = s.first / s.second;
  return out;
}

// v(at) on the increasing grid z, held constant beyond its ends.
inline double interpolate(const std::vector<double>& z, const std::vector<double>& v, double at) {
  if (at <= z.front()) return v.front();
  if (at >= z.back()) return v.back();
  const auto k = std::size_t(std::upper_bound(z.begin(), z.end(), at) - z.begin());
  const double w = (at - z[k - 1]) / (z[k] - z[k - 1]);
  return (1 - w) * v[k - 1] + w * v[k];
}

inline reference::RichardsSoil richards_soil(const SoilMaterial& soil, double porosity, double water_density,
                                             double gravity) {
  reference::RichardsSoil r;
  r.porosity = porosity;
  r.saturated_conductivity = soil.saturated_conductivity;
  const auto model = soil.hydraulic;
  r.saturation = [model](double p_c) { return model.saturation(p_c); };
  r.relative_conductivity = [model](double p_c) { return model.relative_conductivity(p_c); };
  r.water_density = water_density;
  r.gravity = gravity;
  r.water_bulk_modulus = soil.water_bulk_modulus;
  return r;
}

}  // namespace cascade::testing
