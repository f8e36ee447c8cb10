// A small host-side particle set for operator tests: arrays, a sorted neighbour grid and the view
// that kernels take, so a test can call one physical term on chosen particles.
#pragma once

#include <vector>

#include "server/core/cell_sort.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_view.h"
#include "server/physics/equation_of_state.h"

namespace cascade::testing {

template <int Dim>
struct ParticleFixture {
  using V = Vec<double, Dim>;
  using Backend = OmpBackend;
  template <typename T>
  using Vector = Backend::Vector<T>;

  Vector<V> position, velocity, ghost, acceleration, gradient, scratch_vec;
  Vector<double> density, water_density, pressure, density_rate, water_density_rate, step_limit, scratch_real;
  Vector<Phase> phase, scratch_phase;
  SphConstants<double, Dim> sph{};
  WaterConstants<double> water{1000.0, 20.0, 0.1, 0.01};
  GridView<double, Dim> grid{};
  std::unique_ptr<CellSort<double, Dim, Backend>> cells;
  std::unique_ptr<NeighbourList<double, Dim, Backend>> neighbours;
  double h_over_dp;

  ParticleFixture(double dp, double h_over_dp_) : h_over_dp(h_over_dp_) {
    sph.h = h_over_dp * dp;
    sph.kernel = WendlandC2<double, Dim>(sph.h);
    sph.eta2 = 0.01 * sph.h * sph.h;
    sph.mass = water.rho0 * std::pow(dp, Dim);
    sph.gravity = V::Zero();
  }

  void add(const V& x, Phase p, const V& x_ghost = V::Zero()) {
    position.push_back(x);
    velocity.push_back(V::Zero());
    ghost.push_back(p == Phase::boundary ? x_ghost : x);
    phase.push_back(p);
    density.push_back(water.rho0);
    water_density.push_back(water.rho0);
  }

  // Sorts by cell and sizes the rate arrays; call after adding particles and before kernels.
  void finish(const std::array<double, 3>& lo, const std::array<double, 3>& hi, const std::array<bool, 3>& periodic = {}) {
    cells = std::make_unique<CellSort<double, Dim, Backend>>(lo, hi, periodic, 2 * kListRadius * sph.h);
    cells->sort(position, phase);
    cells->reorder(position, scratch_vec);
    cells->reorder(velocity, scratch_vec);
    cells->reorder(ghost, scratch_vec);
    cells->reorder(density, scratch_real);
    cells->reorder(water_density, scratch_real);
    cells->reorder(phase, scratch_phase);
    grid = cells->view();
    neighbours = std::make_unique<NeighbourList<double, Dim, Backend>>(h_over_dp);
    neighbours->build(grid, position, cells->moving(), nullptr, 0);
    const std::size_t n = position.size();
    for (auto* v : {&pressure, &density_rate, &water_density_rate, &step_limit}) v->assign(n, 0.0);
    for (auto* v : {&acceleration, &gradient}) v->assign(n, V::Zero());
  }

  ParticleView<double, Dim> view() {
    return {raw(position), raw(velocity), raw(density), raw(water_density), raw(pressure), raw(phase), raw(ghost),
            raw(acceleration), raw(density_rate), raw(water_density_rate), raw(gradient), raw(step_limit)};
  }

  template <typename F>
  void run(const F& f) {
    for (std::uint32_t i = 0; i < position.size(); ++i) f(i);
  }
};

}  // namespace cascade::testing
