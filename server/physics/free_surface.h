// Free-surface detection by the position divergence (Eq. 38 with ERRATA.md):
//   ∇·x_i = −Σ_j V_j x_ij·∇_i W_ij,
// which is d (2 or 3) inside the material and falls towards the free surface, where the kernel
// support is cut. A soil particle is on the free surface when ∇·x_i < 1.5 (2D) or < 2.5 (3D).
// Every neighbour counts, water and dummy particles too: soil under water or against a wall is
// not a free surface for rain.
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/neighbour_grid.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_view.h"
#include "server/physics/soil_view.h"

namespace cascade {

template <typename Real, int Dim>
struct FreeSurfaceDetection {
  ParticleView<Real, Dim> p;
  SoilView<Real, Dim> soil;
  GridView<Real, Dim> grid;
  NeighbourListView<Real, Dim> neighbours;
  SphConstants<Real, Dim> sph;

  static constexpr Real kThreshold = Dim == 2 ? Real(1.5) : Real(2.5);

  CASCADE_HD void operator()(std::uint32_t i) const {
    const Vec<Real, Dim> x_i = p.position[i];
    const std::uint32_t* list = neighbours.entries(i);
    const std::uint32_t count = neighbours.size(i);
    Real divergence = 0;
    CASCADE_SIMD(reduction(+ : divergence))
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t j = list[k];
      // Components, not an Eigen vector: GCC vectorises the loop (docs/performance.md, "The neighbour loops").
      const Real r2 = grid.offset(x_i, p.position, j).r2;
      const Real grad_factor = sph.kernel.gradient_factor(std::sqrt(r2));
      divergence -= sph.mass / p.density[j] * grad_factor * r2;  // V_j x_ij·∇_i W_ij
    }
    soil.free_surface[i] = divergence < kThreshold ? 1 : 0;
  }
};

}  // namespace cascade
