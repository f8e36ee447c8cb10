// Solid boundaries: dummy particles whose values come from their ghost nodes (Section 3.3.1).
// A field at the ghost node g is interpolated with first-order consistency (Eqs. 30, 31), or
// taken from the Shepard interpolant (Eq. 33) when |det A_g| < 10⁻³. The soil's fields are
// extrapolated to the dummy particle b with a first-order Taylor series (Eq. 32,
// solid_boundary_soil.h); the water's pressure is carried from g to b with the hydrostatic
// gradient of the wall's momentum balance instead (SolidBoundaryWater, below). Velocities use the
// Shepard interpolant (Eq. 34) and the dummy particle takes the opposite of the ghost's (Eq. 35a):
// no slip and no penetration.
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/neighbour_grid.h"
#include "server/core/particle_view.h"
#include "server/core/small_matrix.h"
#include "server/physics/equation_of_state.h"

namespace cascade {

// Accumulates A_g (Eq. 31) and the right-hand side of Eq. 30 for NumFields scalar fields over
// neighbours of a ghost node. Soil stress and pore-water density reuse it with more fields.
template <typename Real, int Dim, int NumFields>
struct GhostInterpolation {
  static constexpr int N = Dim + 1;
  using Matrix = Eigen::Matrix<Real, N, N>;
  using Moments = Eigen::Matrix<Real, N, NumFields>;
  using Values = Eigen::Matrix<Real, NumFields, 1>;

  Matrix a = Matrix::Zero();
  Moments rhs = Moments::Zero();
  Real shepard = 0;                                   // Σ_j W_gj V_j
  Vec<Real, Dim> velocity = Vec<Real, Dim>::Zero();   // Σ_j v_j W_gj V_j

  // x_gj = x_g − x_j; grad_w = ∇_g W_gj.
  CASCADE_HD void add(Real volume, Real w, const Vec<Real, Dim>& grad_w, const Vec<Real, Dim>& x_gj,
                      const Values& values, const Vec<Real, Dim>& v_j) {
    Eigen::Matrix<Real, N, 1> weights;  // (W, ∂_x W, ∂_y W, ∂_z W) V_j
    weights(0) = w * volume;
    for (int a_ = 0; a_ < Dim; ++a_) weights(1 + a_) = grad_w[a_] * volume;
    Eigen::Matrix<Real, N, 1> offsets;  // (1, x_j − x_g, ...)
    offsets(0) = Real(1);
    for (int a_ = 0; a_ < Dim; ++a_) offsets(1 + a_) = -x_gj[a_];
    a += weights * offsets.transpose();
    rhs += weights * values.transpose();
    shepard += w * volume;
    velocity += (w * volume) * v_j;
  }

  bool CASCADE_HD empty() const { return !(shepard > Real(0)); }

  // Values extrapolated to the dummy particle at x_b (Eq. 32), or the Shepard values (Eq. 33).
  CASCADE_HD Values extrapolate(const Vec<Real, Dim>& x_b, const Vec<Real, Dim>& x_g) const {
    const Real det = determinant(a);
    if (std::fabs(det) >= Real(1e-3)) {
      const Moments solution = inverse(a, det) * rhs;  // row 0: value at g; rows 1..Dim: gradient
      Values out = solution.row(0).transpose();
      const Vec<Real, Dim> offset = x_b - x_g;
      for (int a_ = 0; a_ < Dim; ++a_) out += offset[a_] * solution.row(1 + a_).transpose();
      return out;
    }
    return rhs.row(0).transpose() / shepard;
  }

  // Values at the ghost node itself: the first-order interpolation (Eq. 30), or the Shepard values
  // (Eq. 33) when |det A_g| < 10⁻³. A drained wall (Eq. 36a) mirrors them about its prescribed
  // value instead of extrapolating them.
  CASCADE_HD Values at_ghost() const {
    const Real det = determinant(a);
    if (std::fabs(det) >= Real(1e-3)) return (inverse(a, det) * rhs).row(0).transpose();
    return rhs.row(0).transpose() / shepard;
  }

  // Eq. 34a: Shepard-interpolated velocity at the ghost node.
  CASCADE_HD Vec<Real, Dim> ghost_velocity() const { return velocity / shepard; }
};

// The sums of Eqs. 30, 31, 33 and 34a over the water around a ghost node g, each a scalar of its
// own, with ∇_g W_gj = F x_gj. add() sums over a list of particles in a loop that vectorises
// (docs/performance.md, "The neighbour loops"); interpolation() assembles what
// GhostInterpolation::add would have summed.
template <typename Real, int Dim>
struct WaterGhostSums {
  Real w_sum = 0, w_rho = 0;                        // Σ W V, Σ W V ρ_w
  Real wx[3] = {};                                  // Σ W V x_gj
  Real fx[3] = {};                                  // Σ F V x_gj = Σ ∇W V
  Real f_rho[3] = {};                               // Σ ∇W V ρ_w
  Real fxx[6] = {};                                 // Σ F V x_gj ⊗ x_gj: xx, xy, xz, yy, yz, zz
  Real wv[3] = {};                                  // Σ W V v_j
  bool any_water = false;                           // water within the search radius (2h and the skin)

  // The arguments by value: read through a pointer, GCC does not take them for loop invariants.
  CASCADE_HD void add(GridView<Real, Dim> grid, SphConstants<Real, Dim> sph, ParticleView<Real, Dim> p,
                      Vec<Real, Dim> x_g, const std::uint32_t* list, std::uint32_t count) {
    Real s_w = w_sum, s_w_rho = w_rho, wx0 = wx[0], wx1 = wx[1], wx2 = wx[2], f0 = fx[0], f1 = fx[1], f2 = fx[2];
    Real f_rho0 = f_rho[0], f_rho1 = f_rho[1], f_rho2 = f_rho[2];
    Real fxx00 = fxx[0], fxx01 = fxx[1], fxx02 = fxx[2], fxx11 = fxx[3], fxx12 = fxx[4], fxx22 = fxx[5];
    Real wv0 = wv[0], wv1 = wv[1], wv2 = wv[2];
    CASCADE_SIMD(reduction(+ : s_w, s_w_rho, wx0, wx1, wx2, f0, f1, f2, f_rho0, f_rho1, f_rho2, fxx00, fxx01, fxx02,
                           fxx11, fxx12, fxx22, wv0, wv1, wv2))
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t j = list[k];
      const auto [x0, x1, x2, r2] = grid.offset(x_g, p.position, j);
      const Real r = std::sqrt(r2);
      const Real volume = sph.mass / p.density[j];
      const Real w = sph.kernel.value(r) * volume;
      const Real f = sph.kernel.gradient_factor(r) * volume;
      const Real rho_w = p.water_density[j];
      s_w += w;
      s_w_rho += w * rho_w;
      wx0 += w * x0, wx1 += w * x1, wx2 += w * x2;
      f0 += f * x0, f1 += f * x1, f2 += f * x2;
      f_rho0 += f * x0 * rho_w, f_rho1 += f * x1 * rho_w, f_rho2 += f * x2 * rho_w;
      fxx00 += f * x0 * x0, fxx01 += f * x0 * x1, fxx02 += f * x0 * x2;
      fxx11 += f * x1 * x1, fxx12 += f * x1 * x2, fxx22 += f * x2 * x2;
      wv0 += w * gather_component<0>(p.velocity, j);
      wv1 += w * gather_component<1>(p.velocity, j);
      wv2 += w * gather_component<2>(p.velocity, j);
    }
    w_sum = s_w, w_rho = s_w_rho;
    wx[0] = wx0, wx[1] = wx1, wx[2] = wx2, fx[0] = f0, fx[1] = f1, fx[2] = f2;
    f_rho[0] = f_rho0, f_rho[1] = f_rho1, f_rho[2] = f_rho2;
    fxx[0] = fxx00, fxx[1] = fxx01, fxx[2] = fxx02, fxx[3] = fxx11, fxx[4] = fxx12, fxx[5] = fxx22;
    wv[0] = wv0, wv[1] = wv1, wv[2] = wv2;
    any_water = any_water || count > 0;
  }

  // A_g (Eq. 31) and the right-hand side of Eq. 30: rows (W, ∂_x W, ...) V_j, columns
  // (1, x_j − x_g, ...) = (1, −x_gj, ...).
  CASCADE_HD GhostInterpolation<Real, Dim, 1> interpolation() const {
    GhostInterpolation<Real, Dim, 1> ghost;
    ghost.a(0, 0) = w_sum;
    ghost.rhs(0, 0) = w_rho;
    ghost.shepard = w_sum;
    for (int r = 0; r < Dim; ++r) {
      ghost.a(0, 1 + r) = -wx[r];
      ghost.a(1 + r, 0) = fx[r];
      ghost.rhs(1 + r, 0) = f_rho[r];
      ghost.velocity[r] = wv[r];
      for (int c = 0; c < Dim; ++c) ghost.a(1 + r, 1 + c) = -fxx[symmetric_index(r, c)];
    }
    return ghost;
  }
};

// Water side of the solid boundary: p_w of each dummy particle from the water around its ghost
// node (Eqs. 30, 31, 33b) and the hydrostatic gradient, ρ_w from p_w (Eq. 6), velocity from
// Eqs. 34a, 35a. A dummy particle with no water near its ghost node rests at ρ_w0.
//
// Which dummy particles a step computes (flags per particle, set by DummyVisibility at each list
// build and by SolidBoundaryWater at the step's first evaluation):
// - kListed: some moving particle lists the dummy. One that none lists is read by no pass until
//   the lists are built again, and shows the rest values (ρ_w0, p = 0, v = 0) meanwhile; in the
//   3D dam break at 0.004 s that is about 110,000 of 134,391 (the dry walls and the layer farthest
//   from the water).
// - kWet: water was within the search radius (2h and the neighbour-list skin) of its ghost at the
//   step's start. At the half step a dummy without it is skipped: the water has moved less than
//   the skin since, so the ghost still sees none and the rest values written then still hold.
constexpr std::uint8_t kListed = 1, kWet = 2;

template <typename Real, int Dim>
struct SolidBoundaryWater {
  ParticleView<Real, Dim> p;
  GridView<Real, Dim> grid;
  SphConstants<Real, Dim> sph;
  WaterConstants<Real> water;
  std::uint8_t* flags = nullptr;  // per particle, kListed | kWet; none: every dummy is computed
  bool half_step = false;

  CASCADE_HD void operator()(std::uint32_t b) const {
    if (p.phase[b] != Phase::boundary) return;
    if (flags && !(flags[b] & kListed)) {
      if (!half_step) rest(b);
      return;
    }
    if (half_step && flags && !(flags[b] & kWet)) return;
    const Vec<Real, Dim> x_g = p.ghost[b];
    // The water within the search radius is listed in chunks of 128, each summed in a vectorised
    // loop. A cell range is listed a block of 64 candidates at a time: their squared distances in
    // a vectorised loop, then the indices of those within the radius, without a branch on the
    // distance (an index is written, then kept or overwritten): whether a candidate lies within
    // the radius is near random, and mispredicted branches cost more than the stores. What a
    // block lists past a full chunk starts the next one, so the chunks, and the order of the sums,
    // are those of a listing one candidate at a time.
    WaterGhostSums<Real, Dim> sums;
    constexpr std::uint32_t kChunk = 128, kBlock = 64;
    std::uint32_t listed[kChunk + kBlock];
    Real r2[kBlock];
    std::uint32_t count = 0;
    using Grid = GridView<Real, Dim>;
    grid.template for_each_range_in<Grid::kWaterBlock, Grid::kWaterBlock + 1>(
        x_g, [&](std::uint32_t begin, std::uint32_t end) {
      for (std::uint32_t first = begin; first < end; first += kBlock) {
        const std::uint32_t n = end - first < kBlock ? end - first : kBlock;
        CASCADE_SIMD()
        for (std::uint32_t k = 0; k < n; ++k) r2[k] = grid.offset(x_g, p.position, first + k).r2;
        for (std::uint32_t k = 0; k < n; ++k) {
          listed[count] = first + k;
          count += r2[k] < grid.search2 ? 1u : 0u;
        }
        if (count >= kChunk) {
          sums.add(grid, sph, p, x_g, listed, kChunk);
          count -= kChunk;
          for (std::uint32_t k = 0; k < count; ++k) listed[k] = listed[kChunk + k];
        }
      }
    });
    sums.add(grid, sph, p, x_g, listed, count);
    const GhostInterpolation<Real, Dim, 1> ghost = sums.interpolation();
    if (flags && !half_step) flags[b] = sums.any_water ? kListed | kWet : kListed;
    if (ghost.empty()) {
      rest(b);
      return;
    }
    // The ghost node's pressure (Eq. 6 of the value of Eq. 30, or of Eq. 33b's Shepard value),
    // carried to the dummy with the pressure gradient that the momentum balance gives at a fixed
    // wall, ∇p·(x_b − x_g) = ρ_w0 g·(x_b − x_g): the hydrostatic term of Adami, Hu & Adams (2012),
    // Eq. 27, with the wall's acceleration a_w = 0. Eq. 32b's gradient, interpolated from the
    // water near the ghost, is not used: where a ghost node lies in a sliding soil mass it sees a
    // thin film of water, and the extrapolation over |x_b − x_g| (up to 5 dp) gave dummies −34 kPa
    // beside water at a few kPa (docs/physics.md, "Solid boundary"). Exact for a hydrostatic
    // field, as Eq. 32b is.
    const Real p_g = water.pressure(ghost.at_ghost()(0));
    const Real p_b = p_g + water.rho0 * sph.gravity.dot(p.position[b] - x_g);
    p.water_density[b] = water.density(p_b);
    p.pressure[b] = p_b;
    p.velocity[b] = -ghost.ghost_velocity();
  }

 private:
  // A dummy with no water near its ghost, or one no particle lists, rests at ρ_w0.
  CASCADE_HD void rest(std::uint32_t b) const {
    p.water_density[b] = water.rho0;
    p.pressure[b] = 0;
    p.velocity[b] = Vec<Real, Dim>::Zero();
  }
};

// kListed for each dummy particle within the lists' search radius of a water or soil particle at
// the positions the lists were built at: exactly those that some list holds. The radius has a
// margin of 10⁻³ in r² over the lists' own, whose r² is summed in another order, so that no
// listed dummy can be missed by a rounding.
template <typename Real, int Dim>
struct DummyVisibility {
  GridView<Real, Dim> grid;
  const Vec<Real, Dim>* position;
  std::uint8_t* flags;

  CASCADE_HD void operator()(std::uint32_t b) const {
    const Vec<Real, Dim> x_b = position[b];
    const Real radius2 = grid.search2 * Real(1.001);
    using Grid = GridView<Real, Dim>;
    unsigned listed = 0;
    grid.template for_each_range_in<Grid::kWaterBlock, Grid::kSoilBlock + 1>(
        x_b, [&](std::uint32_t begin, std::uint32_t end) {
      CASCADE_SIMD(reduction(| : listed))
      for (std::uint32_t j = begin; j < end; ++j) listed |= grid.offset(x_b, position, j).r2 < radius2 ? 1u : 0u;
    });
    flags[b] = listed ? kListed : 0;
  }
};

}  // namespace cascade
