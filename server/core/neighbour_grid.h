// Cell-linked neighbour grid. Particles are sorted by cell key every step so that the particles of
// one cell, and of a row of cells along x, are contiguous in memory. Particles come in three
// blocks, water, soil and the fixed dummy particles, each sorted by cell: the sort key of a
// particle in cell k is b · ncells + k for block b. `cell_start[k]` is the first particle with
// key k and `cell_start[3 ncells]` the number of particles inside the domain. A row of cells is
// one range in each block; ghost nodes, which gather from moving particles only, read two. So the
// phase of a particle follows from its index (water below water_end, soil below moving_end),
// which neighbour loops test without loading a phase byte.
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/types.h"

namespace cascade {

template <typename Real, int Dim>
struct GridView {
  // Cells are half the kernel support (h) wide and a search spans two cells each way: 5^Dim cells
  // of h hold 1.7 times fewer candidates than 3^Dim cells of 2h around a 2h sphere in 3D.
  static constexpr int kReach = 2;
  static constexpr std::uint32_t kBlocks = 3;  // water, soil, dummy
  static constexpr int kWaterBlock = 0, kSoilBlock = 1, kDummyBlock = 2;

  Vec<Real, Dim> origin;   // domain minimum
  Vec<Real, Dim> length;   // domain extent
  Real inv_cell[Dim];      // 1 / cell size per axis (cell size >= 2h / kReach)
  int ncell[Dim];
  bool periodic[Dim];
  Real period[Dim];        // the domain length along a periodic axis, 0 along the others
  Real inv_period[Dim];    // 1 / period, or 0
  bool any_periodic;       // some axis is periodic
  Real search2;            // squared search radius: the kernel support 2h, or 2h and a skin
  const std::uint32_t* cell_start = nullptr;  // 3 ncells + 1 entries
  std::uint32_t water_end = 0;   // particles [0, water_end) are water
  std::uint32_t moving_end = 0;  // [water_end, moving_end) soil, then the dummy particles
  const std::uint32_t* particle_key = nullptr;  // sort key of each particle, as sorted

  CASCADE_HD std::uint32_t cell_count() const {
    std::uint32_t n = 1;
    for (int a = 0; a < Dim; ++a) n *= std::uint32_t(ncell[a]);
    return n;
  }

  // Along a periodic axis a position outside the period falls in the cell of its periodic image.
  CASCADE_HD int cell_coordinate(Real x, int axis) const {
    int c = int(std::floor((x - origin[axis]) * inv_cell[axis]));
    if (periodic[axis]) {
      c %= ncell[axis];
      return c < 0 ? c + ncell[axis] : c;
    }
    if (c < 0) c = 0;
    if (c >= ncell[axis]) c = ncell[axis] - 1;
    return c;
  }

  // False when x lies outside the domain along a non-periodic axis.
  CASCADE_HD bool contains(const Vec<Real, Dim>& x) const {
    for (int a = 0; a < Dim; ++a) {
      if (periodic[a]) continue;
      const Real s = x[a] - origin[a];
      if (!(s >= Real(0) && s <= length[a])) return false;
    }
    return true;
  }

  CASCADE_HD std::uint32_t key(const int* c) const {
    std::uint32_t k = std::uint32_t(c[Dim - 1]);
    for (int a = Dim - 2; a >= 0; --a) k = k * std::uint32_t(ncell[a]) + std::uint32_t(c[a]);
    return k;
  }

  CASCADE_HD std::uint32_t key_of(const Vec<Real, Dim>& x) const {
    if (!contains(x)) return kOutsideKey;
    int c[Dim];
    for (int a = 0; a < Dim; ++a) c[a] = cell_coordinate(x[a], a);
    return key(c);
  }

  // x_i - x_j, the nearest periodic image along periodic axes. Without branches, so that the
  // neighbour loops vectorise: along other axes the period is 0 and the correction vanishes.
  CASCADE_HD Vec<Real, Dim> displacement(const Vec<Real, Dim>& xi, const Vec<Real, Dim>& xj) const {
    Vec<Real, Dim> d = xi - xj;
    for (int a = 0; a < Dim; ++a) d[a] = nearest_image(d[a], a);
    return d;
  }

  // x_i − x_j by components (0 past the dimension) and its squared length, x_j read from the
  // position array: the form a neighbour loop with scalar sums takes, since GCC does not vectorise
  // such a loop when it holds Eigen vectors (docs/performance.md, "The neighbour loops").
  struct Offset {
    Real x0, x1, x2, r2;
  };
  CASCADE_HD Offset offset(const Vec<Real, Dim>& xi, const Vec<Real, Dim>* position, std::uint32_t j) const {
    Offset d;
    d.x0 = along<0>(xi, position, j);
    d.x1 = along<1>(xi, position, j);
    d.x2 = along<2>(xi, position, j);
    d.r2 = d.x0 * d.x0 + d.x1 * d.x1 + d.x2 * d.x2;
    return d;
  }

  // Wraps a position back into the domain along periodic axes.
  CASCADE_HD void wrap(Vec<Real, Dim>& x) const {
    for (int a = 0; a < Dim; ++a)
      if (periodic[a]) x[a] -= length[a] * Real(std::floor((x[a] - origin[a]) / length[a]));
  }

  // Calls f(j, x_ij, r²) for every particle j with |x_ij|² < search2 around position x (j may be the
  // particle at x itself, with x_ij = 0). Cells are visited in a fixed order, so sums over
  // neighbours are deterministic.
  template <typename F>
  CASCADE_HD void for_each_neighbour(const Vec<Real, Dim>& x, const Vec<Real, Dim>* position, F&& f) const {
    for_each_range_in<0, int(kBlocks)>(x, [&](std::uint32_t begin, std::uint32_t end) {
      visit_range(x, begin, end, position, f);
    });
  }

  // As for_each_neighbour, over the particles of blocks [FirstBlock, EndBlock) only: 0 water,
  // 1 soil, 2 dummy (the ghost nodes of a dummy particle gather from one phase).
  template <int FirstBlock, int EndBlock, typename F>
  CASCADE_HD void for_each_neighbour_in(const Vec<Real, Dim>& x, const Vec<Real, Dim>* position, F&& f) const {
    for_each_range_in<FirstBlock, EndBlock>(x, [&](std::uint32_t begin, std::uint32_t end) {
      visit_range(x, begin, end, position, f);
    });
  }

  // Calls f(begin, end) for each contiguous range of particles of blocks [FirstBlock, EndBlock) in
  // the cells around position x: every particle within the search radius of x is in one of them,
  // with others of the same cells. SolidBoundaryWater lists those within its radius from each
  // range without a branch per particle.
  template <int FirstBlock, int EndBlock, typename F>
  CASCADE_HD void for_each_range_in(const Vec<Real, Dim>& x, F&& f) const {
    int c[Dim];
    for (int a = 0; a < Dim; ++a) c[a] = cell_coordinate(x[a], a);
    visit_cells<FirstBlock, EndBlock>(c, f);
  }

  // As for_each_neighbour around particle i, searching from the cell it was sorted into. Every
  // particle is filed under its sorted cell until the next sort, so i finds j exactly when j
  // finds i, even after the half-step has moved them: pair terms stay equal and opposite.
  template <typename F>
  CASCADE_HD void for_each_neighbour_of(std::uint32_t i, const Vec<Real, Dim>* position, F&& f) const {
    int c[Dim];
    const std::uint32_t cells = cell_count();
    std::uint32_t k = particle_key[i];
    k %= cells;
    for (int a = 0; a < Dim; ++a) {
      c[a] = int(k % std::uint32_t(ncell[a]));
      k /= std::uint32_t(ncell[a]);
    }
    const Vec<Real, Dim> x = position[i];
    visit_cells<0, int(kBlocks)>(c, [&](std::uint32_t begin, std::uint32_t end) {
      visit_range(x, begin, end, position, f);
    });
  }

 private:
  template <int A>
  CASCADE_HD Real along(const Vec<Real, Dim>& xi, const Vec<Real, Dim>* position, std::uint32_t j) const {
    if constexpr (A < Dim) return nearest_image(xi[A] - gather_component<A>(position, j), A);
    else return Real(0);
  }

  // A difference d of coordinates along axis a, to the nearest periodic image (unchanged along
  // the other axes, where the period is 0).
  CASCADE_HD Real nearest_image(Real d, int a) const { return d - period[a] * Real(std::rint(d * inv_period[a])); }

  // Calls range(begin, end) for the particles of blocks [FirstBlock, EndBlock) in the cells
  // within kReach of cell c.
  template <int FirstBlock, int EndBlock, typename F>
  CASCADE_HD void visit_cells(const int* c, F&& range) const {
    if constexpr (Dim == 2) {
      for (int dz = -kReach; dz <= kReach; ++dz) {
        int cc[2] = {0, c[1] + dz};
        if (!wrap_cell(cc[1], 1)) continue;
        visit_row<FirstBlock, EndBlock>(c[0], cc, range);
      }
    } else {
      for (int dz = -kReach; dz <= kReach; ++dz) {
        for (int dy = -kReach; dy <= kReach; ++dy) {
          int cc[3] = {0, c[1] + dy, c[2] + dz};
          if (!wrap_cell(cc[1], 1) || !wrap_cell(cc[2], 2)) continue;
          visit_row<FirstBlock, EndBlock>(c[0], cc, range);
        }
      }
    }
  }

  CASCADE_HD bool wrap_cell(int& c, int axis) const {
    if (c >= 0 && c < ncell[axis]) return true;
    if (!periodic[axis]) return false;
    c = (c + ncell[axis]) % ncell[axis];
    return true;
  }

  // The cells cx-kReach..cx+kReach of one row along x: one contiguous range in each block (water,
  // soil, dummy) unless the row wraps around a periodic axis.
  template <int FirstBlock, int EndBlock, typename F>
  CASCADE_HD void visit_row(int cx, int* cc, F& range) const {
    const int n0 = ncell[0];
    const std::uint32_t cells = cell_count();
    int lo = cx - kReach, hi = cx + kReach;
    if (!periodic[0] || (lo >= 0 && hi < n0)) {
      if (lo < 0) lo = 0;
      if (hi > n0 - 1) hi = n0 - 1;
      cc[0] = lo;
      const std::uint32_t first = key(cc);
      cc[0] = hi;
      const std::uint32_t last = key(cc);
      for (int b = FirstBlock; b < EndBlock; ++b) range(cell_start[b * cells + first], cell_start[b * cells + last + 1]);
      return;
    }
    for (int cxn = lo; cxn <= hi; ++cxn) {
      cc[0] = cxn;
      if (!wrap_cell(cc[0], 0)) continue;
      const std::uint32_t k = key(cc);
      for (int b = FirstBlock; b < EndBlock; ++b) range(cell_start[b * cells + k], cell_start[b * cells + k + 1]);
    }
  }

  template <typename F>
  CASCADE_HD void visit_range(const Vec<Real, Dim>& x, std::uint32_t begin, std::uint32_t end,
                              const Vec<Real, Dim>* position, F& f) const {
    for (std::uint32_t j = begin; j < end; ++j) {
      // A scalar loop: the correction costs more than the branch that skips it.
      const Vec<Real, Dim> d = any_periodic ? displacement(x, position[j]) : Vec<Real, Dim>(x - position[j]);
      const Real r2 = d.squaredNorm();
      if (r2 < search2) f(j, d, r2);
    }
  }
};

}  // namespace cascade
