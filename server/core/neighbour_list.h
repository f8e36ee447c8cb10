// Neighbour lists of the moving particles, built once per step from the cell grid with a search
// radius of 2h plus a skin, and read by every pass of the step's two rate evaluations. A list
// entry is checked against the kernel support at the current positions, so the half-step's
// motion (at most Δt v_max <= 0.02 h, since Eq. 24a keeps v_max <= c0/10 and Eq. 40b keeps
// Δt <= 0.2 h/c0) stays inside the skin of 0.1 h.
//
// Storage: a fixed number of slots per moving particle (the lattice count in the search sphere
// with room for compression); a list that overflows makes the builder retry with more slots.
#pragma once

#include <thrust/extrema.h>
#include <thrust/for_each.h>
#include <thrust/iterator/counting_iterator.h>

#include <cmath>
#include <cstdint>

#include "server/core/backend.h"
#include "server/core/neighbour_grid.h"

namespace cascade {

// The skin: lists hold neighbours within kListRadius · 2h.
constexpr double kListRadius = 1.05;

// Lists of the moving particles, which the cell sort puts first: list i belongs to particle i.
template <typename Real, int Dim>
struct NeighbourListView {
  const std::uint32_t* count;  // per list: number of entries
  const std::uint32_t* index;  // per list: `capacity` entries
  std::uint32_t capacity;

  // Calls f(j, x_ij, r²) for every listed neighbour j of i now within the kernel support.
  template <typename F>
  CASCADE_HD void for_each(std::uint32_t i, const GridView<Real, Dim>& grid, Real support2,
                           const Vec<Real, Dim>* position, F&& f) const {
    const std::uint32_t* entries = index + std::size_t(i) * capacity;
    const std::uint32_t n = count[i];
    const Vec<Real, Dim> x_i = position[i];
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t j = entries[k];
      const Vec<Real, Dim> d = grid.displacement(x_i, position[j]);
      const Real r2 = d.squaredNorm();
      if (r2 < support2) f(j, d, r2);
    }
  }
};

template <typename Real, int Dim>
struct FillNeighbourList {
  GridView<Real, Dim> grid;
  const Vec<Real, Dim>* position;
  std::uint32_t* count;
  std::uint32_t* index;
  std::uint32_t capacity;

  CASCADE_HD void operator()(std::uint32_t i) const {
    std::uint32_t* entries = index + std::size_t(i) * capacity;
    std::uint32_t n = 0;
    grid.for_each_neighbour_of(i, position, [&](std::uint32_t j, const Vec<Real, Dim>&, Real) {
      if (j == i) return;
      if (n < capacity) entries[n] = j;
      ++n;  // counts past the capacity: the builder sees the overflow and retries
    });
    count[i] = n;
  }
};

template <typename Real, int Dim, typename Backend>
class NeighbourList {
  template <typename T>
  using Vector = typename Backend::template Vector<T>;

 public:
  // Slots for a list: the lattice points within the list radius, times 1.5 for compressed water.
  NeighbourList(double h_over_dp) {
    const double radius = 2.0 * kListRadius * h_over_dp;
    constexpr double pi = 3.14159265358979323846;
    const double lattice = Dim == 2 ? pi * radius * radius : 4.0 / 3.0 * pi * radius * radius * radius;
    capacity_ = std::uint32_t(std::ceil(1.5 * lattice / 8.0) * 8.0);
  }

  // Builds the lists of the first `moving` particles, the moving ones (sorted by cell; `grid`
  // searches with the list radius).
  void build(const GridView<Real, Dim>& grid, const Vector<Vec<Real, Dim>>& position, std::size_t moving) {
    count_.resize(moving);
    for (;;) {
      index_.resize(moving * capacity_);
      thrust::for_each(Backend::policy(), thrust::counting_iterator<std::uint32_t>(0),
                       thrust::counting_iterator<std::uint32_t>(std::uint32_t(moving)),
                       FillNeighbourList<Real, Dim>{grid, raw(position), raw(count_), raw(index_), capacity_});
      const std::uint32_t longest =
          moving == 0 ? 0 : *thrust::max_element(Backend::policy(), count_.begin(), count_.end());
      if (longest <= capacity_) break;
      capacity_ = (longest + longest / 4 + 7) / 8 * 8;
    }
  }

  NeighbourListView<Real, Dim> view() const { return {raw(count_), raw(index_), capacity_}; }
  std::size_t bytes() const {
    return (count_.capacity() + index_.capacity()) * sizeof(std::uint32_t);
  }

 private:
  std::uint32_t capacity_;
  Vector<std::uint32_t> count_, index_;
};

}  // namespace cascade
