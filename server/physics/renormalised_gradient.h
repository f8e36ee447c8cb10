// Renormalised water-density gradient of the δ-SPH diffusion term (Eqs. 25a, 25b).
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/neighbour_grid.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_view.h"
#include "server/core/small_matrix.h"
#include "server/physics/equation_of_state.h"
#include "server/physics/soil_view.h"

namespace cascade {

// For each water particle (PoreWater false): p_w from Eq. 6, and
//   ⟨∇ρ_w⟩_i^L = L_i Σ_j V_j (ρ_w,j − ρ_w,i) ∇_i W_ij,   L_i = (Σ_j V_j ∇_i W_ij ⊗ x_ji)⁻¹.
// Eq. 25b prints L with a minus sign and the outer product the other way round; with
// ∇_i W_ij = ∂W/∂x_i and x_ji = x_j − x_i the matrix above tends to the identity inside the
// fluid, so that L makes the gradient of a linear field exact (tests/unit/test_water_operators).
// Neighbours are water particles and dummy boundary particles, whose ρ_w the solid boundary
// extrapolates from the water (Eq. 32b). Where the matrix is singular (a particle with too few
// neighbours, e.g. in a splash) the uncorrected gradient is kept.
//
// For each soil particle (PoreWater true) the same gradient of the pore-water density, for the
// δ-term of Eq. 27a (Section 3.2.2: "the δ-SPH scheme is extended to the pore water"), over soil
// and dummy particles, which show their pore-water pressure (Eq. 32b from the soil,
// solid_boundary_soil.h; ρ_w = ρ_w0 (1 + p_w/K_w) with particle i's K_w); and the gradient of the
// pore pressure for the seepage discharge (Eq. 27b), renormalised in the same way over the soil,
// the dummies and the free water, whose pressure is the pore pressure's value at the soil-water
// interface (pressure continuity, Section 3.3). Free water in the stencil keeps it whole at the
// interface: over the soil alone the top layer's one-sided L_i doubles the gradient's response to
// its own pressure, and the seepage then ran away there at K_sat = 1e-3 m/s (docs/physics.md,
// "Soil-water interface"). The paper uses
// the plain SPH gradient in Eq. 27b, which the kernel's lattice normalisation (kernel.h) makes exact
// in the bulk only: where the support is cut it misses up to half the gradient. Each kind is
// launched over its own block of particles (cell_sort.h).
template <typename Real, int Dim, bool PoreWater = false>
struct RenormalisedDensityGradient {
  ParticleView<Real, Dim> p;
  GridView<Real, Dim> grid;
  NeighbourListView<Real, Dim> neighbours;
  SphConstants<Real, Dim> sph;
  WaterConstants<Real> water;
  SoilView<Real, Dim> soil{};  // PoreWater: the soil materials, the dummies' pore pressure; ⟨∇p_w⟩^L out
  Real rho0 = 0;               // PoreWater: ρ_w0

  static constexpr Real kMinDeterminant = Real(1e-3);

  CASCADE_HD void operator()(std::uint32_t i) const {
    const Real rho_w_i = p.water_density[i];
    if constexpr (!PoreWater) p.pressure[i] = water.pressure(rho_w_i);
    const Vec<Real, Dim> x_i = p.position[i];
    const std::uint32_t* list = neighbours.entries(i);
    const std::uint32_t count = neighbours.size(i);
    const std::uint32_t water_end = grid.water_end, dummy_begin = grid.moving_end;
    Real bulk_modulus = 1;
    if constexpr (PoreWater) bulk_modulus = Real(soil.materials[soil.material[i]].water_bulk_modulus);
    const Real p_i = p.pressure[i];
    // Each sum is a scalar of its own and the loop holds no Eigen vector: GCC then vectorises it
    // with the sums in registers (docs/performance.md, "The neighbour loops"). ∇_i W_ij = F x_ij,
    // so the moments V_j ∇_i W_ij ⊗ x_ij are symmetric: six sums each.
    Real g0 = 0, g1 = 0, g2 = 0;  // Σ V_j (ρ_w,j − ρ_w,i) ∇_i W_ij over the particle's own medium
    Real m00 = 0, m01 = 0, m02 = 0, m11 = 0, m12 = 0, m22 = 0;  // its Σ V_j ∇_i W_ij ⊗ x_ij
    Real q0 = 0, q1 = 0, q2 = 0;  // PoreWater: Σ V_j (p_j − p_w,i) ∇_i W_ij, free water included
    Real n00 = 0, n01 = 0, n02 = 0, n11 = 0, n12 = 0, n22 = 0;  // PoreWater: its Σ V_j ∇_i W_ij ⊗ x_ij
    CASCADE_SIMD(reduction(+ : g0, g1, g2, m00, m01, m02, m11, m12, m22, q0, q1, q2, n00, n01, n02, n11, n12, n22))
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t j = list[k];
      const auto [x0, x1, x2, r2] = grid.offset(x_i, p.position, j);
      // V_j F, zero beyond the support 2h.
      const Real volume_factor = sph.mass / p.density[j] * sph.kernel.gradient_factor(std::sqrt(r2));
      // Neighbours of the other medium take no part: the soil for the water, the free water for
      // the soil's pore water (a factor, not a branch: the loop stays vectorised).
      const bool other_medium = PoreWater ? j < water_end : (j >= water_end) & (j < dummy_begin);
      const Real weight = other_medium ? Real(0) : volume_factor;
      Real rho_w_j = p.water_density[j];
      if constexpr (PoreWater) {
        const bool dummy = j >= dummy_begin;
        // Both loads are made and blended by a 0/1 factor (exact for finite pressures): GCC
        // would otherwise mask them, which it cannot do for these gathers, and leave the loop
        // scalar. The dummy index stays in range.
        const Real dummy_p_j = soil.dummy_pore_pressure[dummy ? j - dummy_begin : 0u];
        const Real own_p_j = p.pressure[j];
        const Real dummy_factor = dummy ? Real(1) : Real(0);
        const Real p_j = dummy_factor * dummy_p_j + (Real(1) - dummy_factor) * own_p_j;
        if (dummy) rho_w_j = rho0 * (Real(1) + p_j / bulk_modulus);
        const Real pressure_weight = volume_factor * (p_j - p_i);
        q0 += pressure_weight * x0, q1 += pressure_weight * x1, q2 += pressure_weight * x2;
        n00 += volume_factor * x0 * x0, n01 += volume_factor * x0 * x1, n02 += volume_factor * x0 * x2;
        n11 += volume_factor * x1 * x1, n12 += volume_factor * x1 * x2, n22 += volume_factor * x2 * x2;
      }
      const Real difference = weight * (rho_w_j - rho_w_i);
      g0 += difference * x0, g1 += difference * x1, g2 += difference * x2;
      m00 += weight * x0 * x0, m01 += weight * x0 * x1, m02 += weight * x0 * x2;
      m11 += weight * x1 * x1, m12 += weight * x1 * x2, m22 += weight * x2 * x2;
    }
    p.water_density_gradient[i] = renormalised({g0, g1, g2}, {m00, m01, m02, m11, m12, m22});
    // Into the seepage array, which SeepageDischarge (seepage.h), the next pass, turns into q_w in
    // place: the gradient needs no array of its own.
    if constexpr (PoreWater) soil.seepage[i] = renormalised({q0, q1, q2}, {n00, n01, n02, n11, n12, n22});
  }

 private:
  // L_i times the sum, L_i = (Σ_j V_j ∇_i W_ij ⊗ x_ji)⁻¹ = (−moment)⁻¹ (Eq. 25b); the sum itself
  // where the matrix is singular. moment holds xx, xy, xz, yy, yz, zz.
  CASCADE_HD static Vec<Real, Dim> renormalised(const Real (&sum)[3], const Real (&moment)[6]) {
    Vec<Real, Dim> gradient;
    Mat<Real, Dim> matrix;
    for (int a = 0; a < Dim; ++a) {
      gradient[a] = sum[a];
      for (int b = 0; b < Dim; ++b) matrix(a, b) = -moment[symmetric_index(a, b)];
    }
    const Real det = determinant(matrix);
    return std::fabs(det) > kMinDeterminant ? Vec<Real, Dim>(inverse(matrix, det) * gradient) : gradient;
  }
};

}  // namespace cascade
