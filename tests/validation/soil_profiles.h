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
#include "server/physics/swcc/grain_bound_water.h"
#include "tests/reference/richards_1d.h"
#include "tests/validation/validation_table.h"

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

// The largest max − min of the soil's pore pressure within one layer (the layers of
// layer_pressures): 0 in a laterally uniform column.
inline double largest_layer_pressure_spread(const FieldFrame& f) {
  std::map<double, std::pair<double, double>> bounds;  // z → (min, max)
  const auto* p = f.find("pore_pressure");
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.phase[i] == std::uint8_t(Phase::soil)) {
      const double v = p->values[i];
      const auto [it, fresh] = bounds.try_emplace(std::round(f.position[3 * i + 2] * 1e6) / 1e6, v, v);
      if (!fresh) it->second.first = std::min(it->second.first, v), it->second.second = std::max(it->second.second, v);
    }
  double spread = 0;
  for (const auto& [z, b] : bounds) spread = worst_of(spread, b.second - b.first);
  return spread;
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

// Θ*(p): the pore-water volume per soil volume that the pore-water continuity (Eq. 27a with
// ERRATA.md) conserves in a rigid skeleton. There C_r dρ_w/dt = −ρ_w ∇·q_w, and with
// ρ_w = ρ_w0 (1 + p_w/K_w) (Eq. 6) that is dΘ*/dt = −∇·q_w for
//   Θ*(p) = φ S_w(0) + ∫_0^p C_r(p') / (K_w + p') dp',   C_r = φ (S_w − K_w ∂S_w/∂p_c) (Eq. 28b),
// which tends to φ S_w for incompressible water. Integrated by composite 8-point Gauss–Legendre
// over pieces of at most 1 kPa.
inline double conserved_pore_water_volume(const SoilMaterial& soil, double porosity, double p) {
  static constexpr double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static constexpr double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const double k_w = soil.water_bulk_modulus;
  const auto integrand = [&](double q) {
    return pore_water_capacity(soil.hydraulic, soil.reference_porosity, -q, porosity, k_w) / (k_w + q);
  };
  const int pieces = std::max(1, int(std::ceil(std::fabs(p) / 1000.0)));
  const double width = p / pieces;
  double integral = 0;
  for (int k = 0; k < pieces; ++k) {
    const double mid = (k + 0.5) * width, half = 0.5 * width;
    for (int j = 0; j < 4; ++j) integral += w[j] * half * (integrand(mid + half * x[j]) + integrand(mid - half * x[j]));
  }
  return porosity * saturation_at_porosity(soil.hydraulic, soil.reference_porosity, 0.0, porosity) + integral;
}

// Σ_i V_i Θ*(p_w,i) over the soil particles of a frame (m³, per metre of depth in 2D), with
// V_i = m/ρ_i the particle's volume from its numerical density (Eq. 22).
inline double pore_water_volume(const FieldFrame& f, const SoilMaterial& soil, double particle_mass) {
  const auto* p = f.find("pore_pressure");
  const auto* porosity = f.find("porosity");
  const auto* density = f.find("numerical_density");
  double sum = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.phase[i] == std::uint8_t(Phase::soil))
      sum += particle_mass / density->values[i] * conserved_pore_water_volume(soil, porosity->values[i], p->values[i]);
  return sum;
}

// Particle-to-particle noise of the pore pressure (issue 13, item 5): for each soil particle, the
// value that a linear fit to its soil neighbours within 2h predicts there (weighted least squares
// with the Wendland kernel, the particle itself left out), and the largest |p_i − fit| over the
// particles, with the field's range max p − min p over the soil. A smooth field is fitted to
// O(h² ∂²p) and the fit passes through its odd-even checkerboard, so the residual is the noise.
struct PressureNoise {
  double largest = 0;  // Pa
  double range = 0;    // Pa
  std::size_t particles = 0;  // soil particles with a fit (at least Dim + 2 neighbours)
};

inline PressureNoise pore_pressure_noise(const FieldFrame& f, double h, int dimensions) {
  const auto* p = f.find("pore_pressure");
  std::vector<std::size_t> soil;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.phase[i] == std::uint8_t(Phase::soil)) soil.push_back(i);
  PressureNoise out;
  if (soil.empty()) return out;
  double low = p->values[soil[0]], high = low;
  for (std::size_t i : soil) low = std::min(low, p->values[i]), high = std::max(high, p->values[i]);
  out.range = high - low;
  const int axes[3] = {0, dimensions == 2 ? 2 : 1, 2};  // 2D cases lie in the (x, z) plane
  const int n = dimensions + 1;                          // unknowns: the value and the gradient
  const double support = 2 * h;
  for (std::size_t i : soil) {
    double normal[4][4] = {}, rhs[4] = {};
    int neighbours = 0;
    for (std::size_t j : soil) {
      if (j == i) continue;
      double d[3] = {}, r2 = 0;
      for (int a = 0; a < dimensions; ++a) {
        d[a] = f.position[3 * j + axes[a]] - f.position[3 * i + axes[a]];
        r2 += d[a] * d[a];
      }
      if (r2 >= support * support) continue;
      const double q = std::sqrt(r2) / h, w = std::pow(1 - q / 2, 4) * (2 * q + 1);
      const double basis[4] = {1, d[0], d[1], d[2]};
      for (int a = 0; a < n; ++a) {
        rhs[a] += w * basis[a] * p->values[j];
        for (int b = 0; b < n; ++b) normal[a][b] += w * basis[a] * basis[b];
      }
      ++neighbours;
    }
    if (neighbours < dimensions + 2) continue;
    // Gaussian elimination with partial pivoting on the n × n normal equations.
    for (int c = 0; c < n; ++c) {
      int pivot = c;
      for (int r = c + 1; r < n; ++r)
        if (std::fabs(normal[r][c]) > std::fabs(normal[pivot][c])) pivot = r;
      std::swap(normal[c], normal[pivot]);
      std::swap(rhs[c], rhs[pivot]);
      for (int r = c + 1; r < n; ++r) {
        const double factor = normal[r][c] / normal[c][c];
        for (int k = c; k < n; ++k) normal[r][k] -= factor * normal[c][k];
        rhs[r] -= factor * rhs[c];
      }
    }
    double solution[4] = {};
    for (int r = n - 1; r >= 0; --r) {
      double sum = rhs[r];
      for (int k = r + 1; k < n; ++k) sum -= normal[r][k] * solution[k];
      solution[r] = sum / normal[r][r];
    }
    out.largest = worst_of(out.largest, std::fabs(p->values[i] - solution[0]));
    ++out.particles;
  }
  return out;
}

}  // namespace cascade::testing
