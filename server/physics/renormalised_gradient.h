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
    Mat<Real, Dim> moment = Mat<Real, Dim>::Zero();
    Vec<Real, Dim> sum = Vec<Real, Dim>::Zero();
    neighbours.for_each(i, grid, sph.kernel.support2, p.position, [&](std::uint32_t j, const Vec<Real, Dim>& x_ij, Real r2) {
      if (j == i || p.phase[j] == Phase::soil) return;
      const Real volume = sph.mass / p.density[j];
      const Vec<Real, Dim> grad_w = sph.kernel.gradient_factor(std::sqrt(r2)) * x_ij;
      moment -= volume * grad_w * x_ij.transpose();
      sum += volume * (p.water_density[j] - rho_w_i) * grad_w;
    });
    const Real det = determinant(moment);
    p.water_density_gradient[i] = std::fabs(det) > kMinDeterminant ? Vec<Real, Dim>(inverse(moment, det) * sum) : sum;
  }
};

}  // namespace cascade
