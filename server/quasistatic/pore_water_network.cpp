#include "server/quasistatic/pore_water_network.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "server/core/kernel.h"
#include "server/core/types.h"
#include "server/physics/seepage_exchange.h"

namespace cascade {

namespace {

const std::vector<double>& reals(const EngineState& s, const char* name, std::size_t components) {
  const auto found = s.reals.find(name);
  if (found == s.reals.end() || found->second.size() != s.particles * components)
    throw std::invalid_argument(std::string("the engine state has no array '") + name + "' of the right size");
  return found->second;
}
const std::vector<std::uint32_t>& integers(const EngineState& s, const char* name) {
  const auto found = s.integers.find(name);
  if (found == s.integers.end() || found->second.size() != s.particles)
    throw std::invalid_argument(std::string("the engine state has no array '") + name + "' of the right size");
  return found->second;
}

template <int Dim>
class NetworkBuilder {
  using V = Vec<double, Dim>;

 public:
  NetworkBuilder(const EngineConfig& config, const EngineState& s)
      : config_(config), s_(s), kernel_(config.h), eta2_(0.01 * config.h * config.h) {
    const auto& x = reals(s, "position", Dim);
    position_.resize(s.particles);
    for (std::size_t k = 0; k < s.particles; ++k)
      for (int a = 0; a < Dim; ++a) position_[k][a] = x[k * Dim + a];
    for (int a = 0; a < Dim; ++a) {
      length_[a] = config.domain_max[a] - config.domain_min[a];
      periodic_[a] = config.periodic[a];
    }
    g_ = V::Zero();
    for (int a = 0; a < Dim; ++a) g_[a] = config.gravity[a];
    if (!(g_.norm() > 0)) throw std::invalid_argument("the implicit pore-water stage needs gravity");
  }

  PoreWaterNetwork build() {
    PoreWaterNetwork n;
    const auto& phase = integers(s_, "phase");
    const auto& density = reals(s_, "density", 1);
    const auto& pressure = reals(s_, "pressure", 1);
    const auto& free_surface = integers(s_, "free_surface");
    const auto& wall = integers(s_, "wall");
    const auto& ghost = reals(s_, "ghost", Dim);
    const double mass = config_.water_density * std::pow(config_.dp, Dim);
    n.gamma_w = config_.water_density * g_.norm();

    std::vector<std::int64_t> soil_index(s_.particles, -1);
    for (std::size_t k = 0; k < s_.particles; ++k) {
      if (Phase(phase[k]) != Phase::soil) continue;
      soil_index[k] = std::int64_t(n.soil.size());
      n.soil.push_back(std::uint32_t(k));
      n.volume.push_back(mass / density[k]);
      n.elevation.push_back(elevation(position_[k]));
      n.free_surface.push_back(std::uint8_t(free_surface[k] != 0));
    }
    n.rain_area.assign(n.soil.size(), 0.0);

    bin_particles();
    const double scale = 1.0 / lattice_moment(density, phase);
    for (std::size_t k = 0; k < s_.particles; ++k) {
      if (soil_index[k] < 0) continue;
      const std::uint32_t i = std::uint32_t(soil_index[k]);
      for_each_neighbour(k, [&](std::size_t j, const V& x_ij, double r2) {
        const double weight = scale * pair_weight(n.volume[i], mass / density[j], x_ij, r2);
        // j's periodic image next to i: heads differ by the elevation along the pair, not by the
        // elevation between the stored positions (which on a periodic axis along which gravity
        // has a component, a tilted infinite slope, differ by the period's drop).
        const V image = position_[k] - x_ij;
        switch (Phase(phase[j])) {
          case Phase::soil:
            if (soil_index[j] > std::int64_t(i))
              n.pairs.push_back({i, std::uint32_t(soil_index[j]), weight, elevation(x_ij)});
            break;
          case Phase::water:
            n.fixed.push_back({i, weight, pressure[j] / n.gamma_w + elevation(image), false});
            break;
          case Phase::boundary: {
            if (wall[j] == 0) break;  // impermeable: no flux
            const std::size_t entry = wall[j] - 1;
            if (entry >= config_.drained_walls.size()) throw std::invalid_argument("a dummy names a drained wall that the case does not have");
            V to_ghost;
            for (int a = 0; a < Dim; ++a) to_ghost[a] = ghost[j * Dim + a] - position_[j][a];
            const double gap = to_ghost.norm();
            if (!(gap > 0)) break;  // no ghost node: no face to hold the pressure at
            const V normal = to_ghost / gap;  // out of the wall, into the soil
            const V face = image + 0.5 * to_ghost;
            const double d_b = 0.5 * gap;
            const double d_i = std::max(displacement(position_[k], face).dot(normal), 0.5 * config_.dp);
            n.fixed.push_back({i, weight * (1.0 + d_b / d_i),
                               config_.drained_walls[entry].pore_pressure / n.gamma_w + elevation(face), true});
            break;
          }
        }
      });
    }
    assign_rain(n, phase, soil_index);
    return n;
  }

 private:
  // The elevation of a position, or the rise along a displacement (linear in it).
  double elevation(const V& x) const { return -g_.dot(x) / g_.norm(); }

  // G_ij of the header (pore_water_network.h): V_i times the explicit stage's pair term at
  // (K_i + K_j)/g = 2 and a unit potential difference (seepage_exchange.h), of the other sign.
  double pair_weight(double volume_i, double volume_j, const V& x_ij, double r2) const {
    const V grad_w = kernel_.gradient_factor(std::sqrt(r2)) * x_ij;
    return -volume_i * seepage_exchange_pair<double, Dim>(volume_j, 2.0, 1.0, x_ij, 1.0 / (r2 + eta2_), grad_w);
  }

  // m = tr(Σ_j V_j (−x_ij·∇W_ij/(r² + η²)) x_ij ⊗ x_ij) / d over all neighbours of a particle,
  // which the Laplacian of the pair weights takes for 1: tr(A M) for a quadratic head of Hessian A,
  // and the flux through a plane per unit head gradient is the same moment. On a lattice at
  // h/dp = 1.3 it differs from 1 by a few per cent (the kernel's discrete moments and η²); the
  // weights are divided by its median over the soil particles (those with a full support), so that
  // the soil's conductivity is the one given, not the lattice's.
  double lattice_moment(const std::vector<double>& density, const std::vector<std::uint32_t>& phase) const {
    const double mass = config_.water_density * std::pow(config_.dp, Dim);
    std::vector<double> moments;
    for (std::size_t k = 0; k < s_.particles; ++k) {
      if (Phase(phase[k]) != Phase::soil) continue;
      double m = 0;
      for_each_neighbour(k, [&](std::size_t j, const V& x_kj, double r2) {
        m += 0.5 * pair_weight(1.0, mass / density[j], x_kj, r2) * r2 / Dim;
      });
      moments.push_back(m);
    }
    if (moments.empty()) return 1.0;
    std::nth_element(moments.begin(), moments.begin() + moments.size() / 2, moments.end());
    return moments[moments.size() / 2];
  }

  V displacement(const V& xi, const V& xj) const {
    V d = xi - xj;
    for (int a = 0; a < Dim; ++a)
      if (periodic_[a]) d[a] -= length_[a] * std::rint(d[a] / length_[a]);
    return d;
  }

  using Cell = std::array<std::int64_t, Dim>;
  struct CellHash {
    std::size_t operator()(const Cell& c) const {
      std::size_t h = 0;
      for (int a = 0; a < Dim; ++a) h = h * 1000003u ^ std::size_t(c[a] + (std::int64_t(1) << 40));
      return h;
    }
  };

  Cell cell_of(const V& x) const {
    Cell c;
    for (int a = 0; a < Dim; ++a) {
      c[a] = std::int64_t(std::floor((x[a] - config_.domain_min[a]) / support()));
      if (periodic_[a]) c[a] = wrap(c[a], a);
    }
    return c;
  }
  std::int64_t cells_along(int a) const { return std::max<std::int64_t>(1, std::int64_t(std::floor(length_[a] / support()))); }
  std::int64_t wrap(std::int64_t c, int a) const {
    const std::int64_t m = cells_along(a);
    return ((c % m) + m) % m;
  }
  double support() const { return 2.0 * config_.h; }

  void bin_particles() {
    for (std::size_t k = 0; k < s_.particles; ++k) cells_[cell_of(position_[k])].push_back(std::uint32_t(k));
  }

  // f(j, x_kj, r²) for every particle j != k within the kernel support of particle k.
  template <typename F>
  void for_each_neighbour(std::size_t k, F&& f) const {
    const Cell centre = cell_of(position_[k]);
    Cell offset;
    offset.fill(-1);
    std::vector<Cell> visited;
    while (true) {
      Cell c;
      for (int a = 0; a < Dim; ++a) c[a] = periodic_[a] ? wrap(centre[a] + offset[a], a) : centre[a] + offset[a];
      // A periodic axis of fewer than three cells reaches one cell twice.
      if (std::find(visited.begin(), visited.end(), c) == visited.end()) {
        visited.push_back(c);
        const auto found = cells_.find(c);
        if (found != cells_.end())
          for (const std::uint32_t j : found->second) {
            if (j == k) continue;
            const V x_kj = displacement(position_[k], position_[j]);
            const double r2 = x_kj.squaredNorm();
            if (r2 < kernel_.support2 && r2 > 0) f(j, x_kj, r2);
          }
      }
      int a = 0;
      while (a < Dim && ++offset[a] > 1) offset[a++] = -1;
      if (a == Dim) break;
    }
  }

  // The highest particle of each dp-wide vertical column; a soil particle there takes the rain
  // of the column's area (header).
  void assign_rain(PoreWaterNetwork& n, const std::vector<std::uint32_t>& phase,
                   const std::vector<std::int64_t>& soil_index) const {
    using Column = std::array<std::int64_t, Dim>;  // the last entry unused
    std::map<Column, std::pair<double, std::size_t>> top;
    for (std::size_t k = 0; k < s_.particles; ++k) {
      Column c{};
      for (int a = 0; a + 1 < Dim; ++a)
        c[a] = std::int64_t(std::floor((position_[k][a] - config_.domain_min[a]) / config_.dp));
      const double z = elevation(position_[k]);
      auto [it, fresh] = top.try_emplace(c, z, k);
      if (!fresh && z > it->second.first) it->second = {z, k};
    }
    const double area = std::pow(config_.dp, Dim - 1);
    for (const auto& [column, highest] : top) {
      const std::size_t k = highest.second;
      if (Phase(phase[k]) == Phase::soil) n.rain_area[std::size_t(soil_index[k])] += area;
    }
  }

  const EngineConfig& config_;
  const EngineState& s_;
  WendlandC2<double, Dim> kernel_;
  double eta2_;
  std::vector<V> position_;
  V g_;
  std::array<double, Dim> length_{};
  std::array<bool, Dim> periodic_{};
  std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash> cells_;
};

}  // namespace

PoreWaterNetwork build_pore_water_network(const EngineConfig& config, const EngineState& state) {
  if (state.dimensions != config.dimensions) throw std::invalid_argument("the state and the case differ in dimensions");
  if (config.dimensions == 2) return NetworkBuilder<2>(config, state).build();
  if (config.dimensions == 3) return NetworkBuilder<3>(config, state).build();
  throw std::invalid_argument("dimensions must be 2 or 3");
}

}  // namespace cascade
