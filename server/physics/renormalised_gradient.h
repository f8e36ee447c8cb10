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
    Real moment_sum[Dim * Dim] = {};  // column-major, as Eigen's Mat
    Real gradient_sum[Dim] = {};
    const std::uint32_t* list = neighbours.entries(i);
    const std::uint32_t count = neighbours.size(i);
    // Neighbours of the other medium, [other_begin, other_end), take no part.
    const std::uint32_t other_begin = PoreWater ? 0u : grid.water_end;
    const std::uint32_t other_end = PoreWater ? grid.water_end : grid.moving_end;
    const std::uint32_t dummy_begin = grid.moving_end;
    Real pressure_sum[Dim] = {};   // PoreWater: Σ V_j (p_j − p_w,i) ∇_i W_ij, free water included
    Real pressure_moment_sum[Dim * Dim] = {};  // PoreWater: its Σ V_j ∇_i W_ij ⊗ x_ij
    Real bulk_modulus = 0;
    if constexpr (PoreWater) bulk_modulus = Real(soil.materials[soil.material[i]].water_bulk_modulus);
    const Real p_i = p.pressure[i];
    CASCADE_SIMD(reduction(+ : moment_sum[:Dim * Dim], gradient_sum[:Dim], pressure_sum[:Dim], pressure_moment_sum[:Dim * Dim]))
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t j = list[k];
      const Vec<Real, Dim> x_ij = grid.displacement(x_i, gather(p.position, j));
      // Zero beyond the support 2h.
      bool other_medium;
      if constexpr (PoreWater) other_medium = j < other_end;  // other_begin is 0
      else other_medium = (j >= other_begin) & (j < other_end);
      const Real same_medium = other_medium ? Real(0) : Real(1);
      const Real volume = same_medium * sph.mass / p.density[j];
      const Vec<Real, Dim> grad_w = sph.kernel.gradient_factor(std::sqrt(x_ij.squaredNorm())) * x_ij;
      Real rho_w_j = p.water_density[j];
      Real pressure_difference = 0, pressure_volume = 0;
      if constexpr (PoreWater) {
        const bool dummy = j >= dummy_begin;
        // Both loads are made in a vectorised loop: the dummy index stays in range.
        const Real p_j = dummy ? soil.dummy_pore_pressure[dummy ? j - dummy_begin : 0u] : p.pressure[j];
        if (dummy) rho_w_j = rho0 * (Real(1) + p_j / bulk_modulus);
        pressure_volume = sph.mass / p.density[j];
        pressure_difference = pressure_volume * (p_j - p_i);
      }
      const Real difference = volume * (rho_w_j - rho_w_i);
      for (int a = 0; a < Dim; ++a) {
        gradient_sum[a] += difference * grad_w[a];
        pressure_sum[a] += pressure_difference * grad_w[a];
        for (int b = 0; b < Dim; ++b) {
          moment_sum[b * Dim + a] += volume * grad_w[a] * x_ij[b];  // V ∇W ⊗ x_ij
          if constexpr (PoreWater) pressure_moment_sum[b * Dim + a] += pressure_volume * grad_w[a] * x_ij[b];
        }
      }
    }
    // Σ V_j ∇_i W_ij ⊗ x_ji = −Σ V_j ∇_i W_ij ⊗ x_ij
    const Mat<Real, Dim> moment = -Eigen::Map<const Mat<Real, Dim>>(moment_sum);
    const Vec<Real, Dim> sum = Eigen::Map<const Vec<Real, Dim>>(gradient_sum);
    const Real det = determinant(moment);
    const bool invertible = std::fabs(det) > kMinDeterminant;
    const Mat<Real, Dim> correction = invertible ? inverse(moment, det) : Mat<Real, Dim>::Identity();
    p.water_density_gradient[i] = correction * sum;
    if constexpr (PoreWater) {
      const Mat<Real, Dim> pressure_moment = -Eigen::Map<const Mat<Real, Dim>>(pressure_moment_sum);
      const Real pressure_det = determinant(pressure_moment);
      const Mat<Real, Dim> pressure_correction = std::fabs(pressure_det) > kMinDeterminant
                                                     ? inverse(pressure_moment, pressure_det)
                                                     : Mat<Real, Dim>::Identity();
      // Into the seepage array, which SeepageDischarge (seepage.h), the next pass, turns into q_w in
      // place: the gradient needs no array of its own.
      soil.seepage[i] = pressure_correction * Eigen::Map<const Vec<Real, Dim>>(pressure_sum);
    }
  }
};

}  // namespace cascade
