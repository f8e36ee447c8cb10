// Soil side of the solid boundary (Section 3.3.1): the values that a dummy particle shows its
// soil neighbours, from the soil around its ghost node. Water neighbours see the water side
// (solid_boundary.h); a wall touched by both keeps both.
//  - total stress σ (Eq. 32a): first-order interpolation at the ghost node and Taylor
//    extrapolation to the dummy (Eqs. 30-32a), or the Shepard value (Eq. 33a) when
//    |det A_g| < 10⁻³.
//  - p_w of an impermeable wall: the same interpolation and extrapolation (Eqs. 30-32b, 33b). The
//    paper extrapolates ρ_w; the pressure is the same within one soil (linear Eq. 6) and stays
//    continuous between soils of different K_w, whose densities jump. A soil neighbour reads ρ_w
//    from it with its own K_w (renormalised_gradient.h).
//  - p_w of a drained wall: the prescribed pressure mirrored about the ghost node's value
//    (Eq. 36, drained_wall.h).
//  - v: Shepard interpolation of the soil velocity at the ghost node, reversed at the dummy
//    (Eqs. 34a, 35a): no slip, no penetration, for both kinds of wall.
//  - q_w (Eqs. 34b, 35b, 37) is not formed: the seepage divergence is a sum of pair exchanges
//    (seepage_exchange.h), which an impermeable wall's dummies do not join (no flux through it)
//    and a drained wall's join with the pore pressure above, so that water passes.
#pragma once

#include <cmath>
#include <cstdint>

#include "server/core/neighbour_grid.h"
#include "server/core/particle_view.h"
#include "server/physics/drained_wall.h"
#include "server/physics/soil_view.h"
#include "server/physics/solid_boundary.h"

namespace cascade {

template <typename Real, int Dim>
struct SolidBoundarySoil {
  ParticleView<Real, Dim> p;
  SoilView<Real, Dim> soil;
  GridView<Real, Dim> grid;
  SphConstants<Real, Dim> sph;
  const std::uint8_t* flags = nullptr;  // per particle, kListed (solid_boundary.h); none: every dummy

  CASCADE_HD void operator()(std::uint32_t b) const {
    const std::uint32_t k = b - grid.moving_end;  // the dummy block's index
    const std::uint8_t wall = soil.wall[b];
    const Real prescribed = wall ? soil.wall_pore_pressure[wall - 1] : Real(0);
    // A dummy that no particle lists is read by no pass until the lists are built again
    // (DummyVisibility): it rests.
    if (flags && !(flags[b] & kListed)) {
      rest(k, prescribed);
      return;
    }
    const Vec<Real, Dim> x_g = p.ghost[b];
    GhostInterpolation<Real, Dim, 7> ghost;  // p_w, then the 6 components of σ
    using Grid = GridView<Real, Dim>;
    grid.template for_each_neighbour_in<Grid::kSoilBlock, Grid::kSoilBlock + 1>(
        x_g, p.position, [&](std::uint32_t j, const Vec<Real, Dim>& x_gj, Real r2) {
          const Real r = std::sqrt(r2);
          Eigen::Matrix<Real, 7, 1> values;
          values(0) = p.pressure[j];
          values.template tail<6>() = total_stress(soil.effective_stress[j], soil.saturation[j], p.pressure[j]);
          ghost.add(sph.mass / p.density[j], sph.kernel.value(r), sph.kernel.gradient_factor(r) * x_gj, x_gj, values,
                    p.velocity[j]);
        });
    if (ghost.empty()) {
      rest(k, prescribed);
      return;
    }
    const Eigen::Matrix<Real, 7, 1> values = ghost.extrapolate(p.position[b], x_g);
    soil.dummy_pore_pressure[k] = wall ? drained_wall_pore_pressure(prescribed, ghost.at_ghost()(0)) : values(0);
    soil.dummy_stress[k] = values.template tail<6>();
    soil.dummy_velocity[k] = -ghost.ghost_velocity();
  }

 private:
  // No soil near the ghost: the wall's prescribed pore pressure (0 for an impermeable one), no
  // stress, at rest.
  CASCADE_HD void rest(std::uint32_t k, Real prescribed) const {
    soil.dummy_pore_pressure[k] = prescribed;
    soil.dummy_stress[k] = Voigt<Real>::Zero();
    soil.dummy_velocity[k] = Vec<Real, Dim>::Zero();
  }
};

}  // namespace cascade
