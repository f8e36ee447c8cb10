// Renormalised water-density gradient of the δ-SPH diffusion term (Eqs. 25a, 25b).
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/neighbour_grid.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_view.h"
#include "server/core/small_matrix.h"
#include "server/physics/equation_of_state.h"

namespace cascade {

// For each water particle: p_w from Eq. 6, and
//   ⟨∇ρ_w⟩_i^L = L_i Σ_j V_j (ρ_w,j − ρ_w,i) ∇_i W_ij,   L_i = (Σ_j V_j ∇_i W_ij ⊗ x_ji)⁻¹.
// Eq. 25b prints L with a minus sign and the outer product the other way round; with
// ∇_i W_ij = ∂W/∂x_i and x_ji = x_j − x_i the matrix above tends to the identity inside the
// fluid, so that L makes the gradient of a linear field exact (tests/unit/test_water_operators).
// Neighbours are water particles and dummy boundary particles, whose ρ_w the solid boundary
// extrapolates from the water (Eq. 32b). Where the matrix is singular (a particle with too few
// neighbours, e.g. in a splash) the uncorrected gradient is kept.
template <typename Real, int Dim>
struct RenormalisedDensityGradient {
  ParticleView<Real, Dim> p;
  GridView<Real, Dim> grid;
  NeighbourListView<Real, Dim> neighbours;
  SphConstants<Real, Dim> sph;
  WaterConstants<Real> water;

  static constexpr Real kMinDeterminant = Real(1e-3);

  CASCADE_HD void operator()(std::uint32_t i) const {
    if (p.phase[i] != Phase::water) return;
    const Real rho_w_i = p.water_density[i];
    p.pressure[i] = water.pressure(rho_w_i);
    const Vec<Real, Dim> x_i = p.position[i];
    Real moment_sum[Dim * Dim] = {};  // column-major, as Eigen's Mat
    Real gradient_sum[Dim] = {};
    const std::uint32_t* list = neighbours.entries(i);
    const std::uint32_t count = neighbours.size(i);
    const std::uint32_t soil_begin = grid.water_end, soil_end = grid.moving_end;
    CASCADE_SIMD(reduction(+ : moment_sum[:Dim * Dim], gradient_sum[:Dim]))
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t j = list[k];
      const Vec<Real, Dim> x_ij = grid.displacement(x_i, gather(p.position, j));
      // Soil neighbours take no part (their ρ_w is pore water); zero beyond the support 2h.
      const Real not_soil = (j >= soil_begin) & (j < soil_end) ? Real(0) : Real(1);
      const Real volume = not_soil * sph.mass / p.density[j];
      const Vec<Real, Dim> grad_w = sph.kernel.gradient_factor(std::sqrt(x_ij.squaredNorm())) * x_ij;
      const Real difference = volume * (p.water_density[j] - rho_w_i);
      for (int a = 0; a < Dim; ++a) {
        gradient_sum[a] += difference * grad_w[a];
        for (int b = 0; b < Dim; ++b) moment_sum[b * Dim + a] += volume * grad_w[a] * x_ij[b];  // V ∇W ⊗ x_ij
      }
    }
    // Σ V_j ∇_i W_ij ⊗ x_ji = −Σ V_j ∇_i W_ij ⊗ x_ij
    const Mat<Real, Dim> moment = -Eigen::Map<const Mat<Real, Dim>>(moment_sum);
    const Vec<Real, Dim> sum = Eigen::Map<const Vec<Real, Dim>>(gradient_sum);
    const Real det = determinant(moment);
    p.water_density_gradient[i] = std::fabs(det) > kMinDeterminant ? Vec<Real, Dim>(inverse(moment, det) * sum) : sum;
  }
};

}  // namespace cascade
