// Builds the neighbour grid each step: cell key of every particle, a stable sort by key (so the
// order is deterministic), and the first particle of every cell (DESIGN.md, "One step").
#pragma once

#include <thrust/binary_search.h>
#include <thrust/for_each.h>
#include <thrust/gather.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "server/core/backend.h"
#include "server/core/neighbour_grid.h"

namespace cascade {

// Sort key of a particle in cell k: block · ncells + k, the block being its phase (water 0,
// soil 1, dummy 2; neighbour_grid.h); kOutsideKey outside the domain.
template <typename Real, int Dim>
struct CellKeyOf {
  GridView<Real, Dim> grid;
  const Vec<Real, Dim>* position;
  const Phase* phase;
  std::uint32_t* key;
  CASCADE_HD void operator()(std::uint32_t i) const {
    const std::uint32_t cell = grid.key_of(position[i]);
    key[i] = cell == kOutsideKey ? kOutsideKey : cell + std::uint32_t(phase[i]) * grid.cell_count();
  }
};

template <typename Real, int Dim, typename Backend>
class CellSort {
  template <typename T>
  using Vector = typename Backend::template Vector<T>;

 public:
  // Cells are at least search_radius / kReach wide; along a periodic axis a whole number of them
  // spans the period, and at least 2 kReach + 1 of them, so that a search never visits a cell
  // twice. The search radius is the kernel support 2h, or 2h and a skin for neighbour lists.
  CellSort(const std::array<double, 3>& domain_min, const std::array<double, 3>& domain_max,
           const std::array<bool, 3>& periodic, double search_radius) {
    constexpr int reach = GridView<Real, Dim>::kReach;
    const double support = search_radius;
    const double cell = support / reach;
    std::uint64_t cells = 1;
    for (int a = 0; a < Dim; ++a) {
      const double length = domain_max[a] - domain_min[a];
      if (!(length > 0)) throw std::invalid_argument("domain is empty along axis " + std::to_string(a));
      grid_.origin[a] = Real(domain_min[a]);
      grid_.length[a] = Real(length);
      grid_.periodic[a] = periodic[a];
      grid_.any_periodic = grid_.any_periodic || periodic[a];
      grid_.period[a] = periodic[a] ? Real(length) : Real(0);
      grid_.inv_period[a] = periodic[a] ? Real(1.0 / length) : Real(0);
      int n = periodic[a] ? int(std::floor(length / cell)) : int(std::ceil(length / cell));
      if (n < 1) n = 1;
      if (periodic[a] && (n < 2 * reach + 1 || length < 3 * support))
        throw std::invalid_argument("periodic axis " + std::to_string(a) +
                                    " must span at least three kernel supports (6h and the neighbour-list skin)");
      grid_.ncell[a] = n;
      grid_.inv_cell[a] = Real(periodic[a] ? n / length : 1.0 / cell);
      cells *= std::uint64_t(n);
    }
    if (GridView<Real, Dim>::kBlocks * cells >= kOutsideKey) throw std::invalid_argument("domain holds too many cells for 32-bit cell keys");
    grid_.search2 = Real(support * support);
    cell_start_.resize(GridView<Real, Dim>::kBlocks * cells + 1);
    grid_.cell_start = raw(cell_start_);
  }

  // A copy's grid view points into the copy's own arrays.
  CellSort(const CellSort& other)
      : grid_(other.grid_), key_(other.key_), order_(other.order_), cell_start_(other.cell_start_),
        active_(other.active_), moving_(other.moving_) {
    grid_.cell_start = raw(cell_start_);
    if (grid_.particle_key) grid_.particle_key = raw(key_);
  }
  CellSort& operator=(const CellSort&) = delete;

  // Sorts by cell: afterwards order()[k] is the old index of the particle now at k; call
  // reorder() on every per-particle field. Particles outside the domain go last.
  void sort(const Vector<Vec<Real, Dim>>& position, const Vector<Phase>& phase) {
    const std::size_t n = position.size();
    key_.resize(n);
    order_.resize(n);
    thrust::for_each(Backend::policy(), thrust::counting_iterator<std::uint32_t>(0),
                     thrust::counting_iterator<std::uint32_t>(std::uint32_t(n)),
                     CellKeyOf<Real, Dim>{grid_, raw(position), raw(phase), raw(key_)});
    thrust::sequence(Backend::policy(), order_.begin(), order_.end());
    thrust::stable_sort_by_key(Backend::policy(), key_.begin(), key_.end(), order_.begin());
    const std::uint32_t cells = grid_.cell_count();
    const std::uint32_t groups = GridView<Real, Dim>::kBlocks * cells;
    thrust::lower_bound(Backend::policy(), key_.begin(), key_.end(), thrust::counting_iterator<std::uint32_t>(0),
                        thrust::counting_iterator<std::uint32_t>(groups + 1), cell_start_.begin());
    active_ = cell_start_[groups];
    moving_ = cell_start_[2 * cells];
    grid_.water_end = cell_start_[cells];
    grid_.moving_end = std::uint32_t(moving_);
    grid_.particle_key = raw(key_);
  }

  template <typename T>
  void reorder(Vector<T>& field, Vector<T>& scratch) const {
    scratch.resize(field.size());
    thrust::gather(Backend::policy(), order_.begin(), order_.end(), field.begin(), scratch.begin());
    field.swap(scratch);
  }

  const GridView<Real, Dim>& view() const { return grid_; }
  std::size_t active() const { return active_; }  // particles inside the domain, first in order
  std::size_t moving() const { return moving_; }  // moving particles inside the domain, first of all
  std::size_t bytes() const {
    return (key_.capacity() + order_.capacity() + cell_start_.capacity()) * sizeof(std::uint32_t);
  }

 private:
  GridView<Real, Dim> grid_{};
  Vector<std::uint32_t> key_, order_, cell_start_;
  std::size_t active_ = 0;
  std::size_t moving_ = 0;
};

}  // namespace cascade
