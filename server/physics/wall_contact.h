// The impenetrable wall: no matter enters a rigid solid. The dummy particles' pressures and
// stresses (Eqs. 30-35) push water and soil away from a wall, but a pressure acts only through the
// kernel sums, over a step: a particle driven hard enough at a wall (the water wedge under a slide's
// front, a splash, a heavy soil front) is carried across the wall's surface within a step, and
// once among the dummies it meets pairs on every side and is not pushed back out (the landslide
// flume lost 4 water particles through its slope, docs/physics.md, "Impenetrable walls").
//
// The condition imposed here is the kinematic one of a rigid wall at rest, x on the fluid side of
// the surface and v·n >= 0 where x is on it, n the surface's outward normal. After each position
// update a particle whose centre lies inside the wall is put back onto its surface along n, and its
// velocity into the wall is removed (a perfectly inelastic impact; the tangential velocity is kept,
// the no-slip dummies act on it). The surface near a particle is that of its nearest dummy b: the
// wetted point s_b = (x_b + x_g)/2 halfway to its ghost node x_g and the normal
// n = (x_g − x_b)/|x_g − x_b| (Section 3.3.1: x_g is the mirror image of x_b across the surface), a
// plane for a flat face and the tangent plane at an edge or corner. A particle outside every wall
// is not touched: the condition adds nothing where the pressures hold the wall.
#pragma once

#include <cstdint>
#include <limits>

#include "server/core/neighbour_grid.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_view.h"

namespace cascade {

template <typename Real, int Dim>
struct WallContact {
  ParticleView<Real, Dim> p;
  GridView<Real, Dim> grid;
  NeighbourListView<Real, Dim> neighbours;

  CASCADE_HD void operator()(std::uint32_t i) const {
    using V = Vec<Real, Dim>;
    const V x_i = p.position[i];
    const std::uint32_t* list = neighbours.entries(i);
    const std::uint32_t count = neighbours.size(i);
    Real nearest2 = std::numeric_limits<Real>::max();
    std::uint32_t nearest = count;  // none
    V x_ib = V::Zero();
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t j = list[k];
      if (j < grid.moving_end) continue;  // dummies only
      const V d = grid.displacement(x_i, p.position[j]);
      const Real r2 = d.squaredNorm();
      if (r2 < nearest2) nearest2 = r2, nearest = j, x_ib = d;
    }
    if (nearest == count) return;
    const V mirror = grid.displacement(p.ghost[nearest], p.position[nearest]);  // x_g − x_b = 2 (s_b − x_b)
    const Real length = mirror.norm();
    if (!(length > Real(0))) return;
    const V normal = mirror / length;
    const Real depth = (Real(0.5) * mirror - x_ib).dot(normal);  // (s_b − x_i)·n, > 0 inside the wall
    if (!(depth > Real(0))) return;
    V x = x_i + depth * normal;
    grid.wrap(x);
    p.position[i] = x;
    const Real inward = p.velocity[i].dot(normal);
    if (inward < Real(0)) p.velocity[i] -= inward * normal;
  }
};

}  // namespace cascade
