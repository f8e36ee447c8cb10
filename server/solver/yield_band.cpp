#include "server/solver/yield_band.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "server/core/types.h"

namespace cascade {

namespace {

// Union-find over particle indices.
struct Components {
  std::vector<std::size_t> parent;
  explicit Components(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t(0)); }
  std::size_t root(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) { parent[root(a)] = root(b); }
};

std::string text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

}  // namespace

YieldBandMeasure measure_yield_band(const FieldFrame& frame, const YieldBandCriterion& criterion, double dp) {
  const auto* ratio = frame.find("yield_ratio");
  if (!ratio) throw std::invalid_argument("the frame has no yield_ratio field (a case without soil)");
  YieldBandMeasure m;
  std::vector<std::size_t> yielded;
  for (std::size_t i = 0; i < frame.size(); ++i)
    if (frame.phase[i] == std::uint8_t(Phase::soil) && ratio->values[i] >= criterion.ratio) yielded.push_back(i);
  m.yielded = yielded.size();
  m.volume = double(yielded.size()) * std::pow(dp, frame.dimensions);
  if (!criterion.connected || yielded.empty()) return m;

  // Neighbours within 1.5 dp, found through cells of that size.
  const double reach = 1.5 * dp;
  using Cell = std::array<std::int64_t, 3>;
  std::map<Cell, std::vector<std::size_t>> cells;
  const auto cell_of = [&](std::size_t i) {
    Cell c;
    for (int a = 0; a < 3; ++a) c[a] = std::int64_t(std::floor(frame.position[3 * i + a] / reach));
    return c;
  };
  for (std::size_t k = 0; k < yielded.size(); ++k) cells[cell_of(yielded[k])].push_back(k);
  Components components(yielded.size());
  for (std::size_t k = 0; k < yielded.size(); ++k) {
    const Cell c = cell_of(yielded[k]);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (found == cells.end()) continue;
          for (const std::size_t l : found->second) {
            if (l <= k) continue;
            double r2 = 0;
            for (int a = 0; a < 3; ++a) {
              const double d = frame.position[3 * yielded[k] + a] - frame.position[3 * yielded[l] + a];
              r2 += d * d;
            }
            if (r2 <= reach * reach) components.join(k, l);
          }
        }
  }
  // Per connected set, the bounding box of its free-surface members: a set that reaches the free
  // surface at two points that far apart cuts the soil from surface to surface (a slip surface
  // that daylights at both ends); its diagonal is the set's span. A set that reaches the surface
  // at one place only (a band along the bedrock from the toe) has a span of about dp.
  std::map<std::size_t, std::array<double, 6>> boxes;
  for (std::size_t k = 0; k < yielded.size(); ++k) {
    const std::size_t i = yielded[k];
    if (frame.free_surface.empty() || !frame.free_surface[i]) continue;
    auto [it, fresh] = boxes.try_emplace(components.root(k));
    auto& box = it->second;
    for (int a = 0; a < 3; ++a) {
      const double x = frame.position[3 * i + a];
      box[a] = fresh ? x : std::min(box[a], x);
      box[3 + a] = fresh ? x : std::max(box[3 + a], x);
    }
  }
  for (const auto& [root, box] : boxes) {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += (box[3 + a] - box[a]) * (box[3 + a] - box[a]);
    m.connected_span = std::max(m.connected_span, std::sqrt(d2));
  }
  return m;
}

std::string yield_band_reached(const YieldBandMeasure& m, const YieldBandCriterion& c) {
  if (c.volume > 0 && m.volume > c.volume)
    return "yielded volume " + text(m.volume) + " > " + text(c.volume) + " (" + std::to_string(m.yielded) +
           " particles at yield ratio >= " + text(c.ratio) + ")";
  if (c.connected && m.connected_span >= c.span)
    return "a connected yielded band meets the free surface at points " + text(m.connected_span) + " m apart (>= " +
           text(c.span) + " m; " + std::to_string(m.yielded) + " particles at yield ratio >= " + text(c.ratio) + ")";
  return "";
}

}  // namespace cascade
