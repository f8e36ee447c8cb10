// Neighbour lists of the moving particles, built from the cell grid with a search radius of 2h
// plus a skin s = 0.1 h, and read by every pass of the rate evaluations. A list entry is checked
// against the kernel support at the current positions (the kernel is zero beyond 2h), so a list
// stays valid while every particle is within s/2 of where it was when the lists were built: a
// pair within 2h now was then within 2h + s. The engine keeps the cell sort and the lists over
// several steps and rebuilds both when a particle could pass s/2 before the step's half-step
// evaluation (ListDrift below, simulation.h).
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
// A pass loops over a list itself (a plain loop the host compiler vectorises, CASCADE_SIMD) and
// lets the kernel, which is zero beyond 2h, drop the entries of the skin.
template <typename Real, int Dim>
struct NeighbourListView {
  const std::uint32_t* count;  // per list: number of entries
  const std::uint32_t* index;  // per list: `capacity` entries
  std::uint32_t capacity;

  CASCADE_HD const std::uint32_t* entries(std::uint32_t i) const { return index + std::size_t(i) * capacity; }
  CASCADE_HD std::uint32_t size(std::uint32_t i) const { return count[i]; }
};

template <typename Real, int Dim>
struct FillNeighbourList {
  GridView<Real, Dim> grid;
  const Vec<Real, Dim>* position;
  std::uint32_t* count;
  std::uint32_t* index;
  std::uint32_t capacity;
  const std::uint32_t* owner;  // split over processes: per particle, its owner; else null
  std::uint32_t process;       // this one

  CASCADE_HD void operator()(std::uint32_t i) const {
    // A copy of another process's particle: no pass reads its list (Simulation::launch_owned; its
    // state is its owner's, refresh_halo), so it gets none.
    if (owner && owner[i] != process) {
      count[i] = 0;
      return;
    }
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

// How far particle i may be from its position at the last list build by the end of the step's
// half-step predictor: its drift so far plus ½ Δt_max |v_i|, the predictor's motion
// (symplectic_verlet.h) for the largest step the coming step can take.
template <typename Real, int Dim>
struct ListDrift {
  GridView<Real, Dim> grid;
  const Vec<Real, Dim>* position;
  const Vec<Real, Dim>* listed_position;
  const Vec<Real, Dim>* velocity;
  Real half_max_dt;

  CASCADE_HD Real operator()(std::uint32_t i) const {
    return grid.displacement(position[i], listed_position[i]).norm() + half_max_dt * velocity[i].norm();
  }
};

template <typename Real>
struct MaximumOf {
  CASCADE_HD Real operator()(Real a, Real b) const { return a > b ? a : b; }
};

template <typename Real, int Dim, typename Backend>
class NeighbourList {
  template <typename T>
  using Vector = typename Backend::template Vector<T>;

 public:
  // Slots for a list: the lattice points within the list radius, times 1.25 for compressed or
  // disordered particles; a fuller list makes build() retry with room for it.
  NeighbourList(double h_over_dp) {
    const double radius = 2.0 * kListRadius * h_over_dp;
    constexpr double pi = 3.14159265358979323846;
    const double lattice = Dim == 2 ? pi * radius * radius : 4.0 / 3.0 * pi * radius * radius * radius;
    capacity_ = std::uint32_t(std::ceil(1.25 * lattice / 8.0) * 8.0);
  }

  // A copy has the slot count but no lists: it is built() again before use. The lists follow
  // from the positions they were built at, which the engine keeps (Simulation::clone: a fork
  // lists in its own thread instead of copying the largest array at its parent's step).
  NeighbourList(const NeighbourList& other) : capacity_(other.capacity_) {}
  NeighbourList& operator=(const NeighbourList&) = delete;
  bool built() const { return built_; }

  // Builds the lists of the first `moving` particles, the moving ones (sorted by cell; `grid`
  // searches with the list radius). Split over processes (`owner` not null), of those that
  // `process` owns: the copies' lists are empty.
  void build(const GridView<Real, Dim>& grid, const Vector<Vec<Real, Dim>>& position, std::size_t moving,
             const std::uint32_t* owner, std::uint32_t process) {
    count_.resize(moving);
    for (;;) {
      index_.resize(moving * capacity_);
      thrust::for_each(Backend::policy(), thrust::counting_iterator<std::uint32_t>(0),
                       thrust::counting_iterator<std::uint32_t>(std::uint32_t(moving)),
                       FillNeighbourList<Real, Dim>{grid, raw(position), raw(count_), raw(index_), capacity_,
                                                    owner, process});
      const std::uint32_t longest =
          moving == 0 ? 0 : *thrust::max_element(Backend::policy(), count_.begin(), count_.end());
      if (longest <= capacity_) break;
      capacity_ = (longest + longest / 4 + 7) / 8 * 8;
    }
    built_ = true;
  }

  NeighbourListView<Real, Dim> view() const { return {raw(count_), raw(index_), capacity_}; }
  const Vector<std::uint32_t>& counts() const { return count_; }  // entries per list
  std::size_t bytes() const {
    return (count_.capacity() + index_.capacity()) * sizeof(std::uint32_t);
  }

 private:
  std::uint32_t capacity_;
  bool built_ = false;
  Vector<std::uint32_t> count_, index_;
};

}  // namespace cascade
