// The pore water that crosses the soil's boundaries, per particle and per second, so that the
// engine can integrate what came in and what left (Simulation::pore_water_account). Inside the
// soil the pairwise Darcy exchanges are antisymmetric (seepage_exchange.h) and move water without
// creating it; what changes the soil's pore water is, per particle i with volume V_i = m/ρ_i:
//  - rain: the source of Eq. 39 on the flux-state particle that tops its column, i dp^(d−1);
//  - drained walls: V_i s Σ_{dummies j} w_ij (Φ_i − Φ_j), the exchange with a drained wall's
//    dummies (Eq. 36);
//  - surfaces with a prescribed pressure (ponded, drying, held; a seepage face is a ponded one):
//    at a particle that holds its pressure, −V_i s Σ_{soil j} w_ij (Φ_i − Φ_j), since its own pore
//    water does not change and what its soil neighbours send it leaves through the surface (its
//    own wall and missing pairs lead from outside to outside and do not count); and at a particle
//    that does not, the flux of the pairs its cut support lacks beside one,
//    −V_i s ∇Φ_i·Σ_j w_ij x_ij (seepage_exchange.h).
// Each is positive where water enters the soil. The balance ΔΣ V_i Θ*_i = rain + walls + surface
// then holds to the time integration's error (tests/validation/test_pore_water_balance.cpp).
#pragma once

#include <cstdint>

#include "server/core/types.h"

namespace cascade {

template <typename Real>
struct PoreWaterInflow {
  Real rain;     // m³/s (m²/s per metre of depth in 2D)
  Real walls;
  Real surface;

  CASCADE_HD PoreWaterInflow operator+(const PoreWaterInflow& o) const {
    return {rain + o.rain, walls + o.walls, surface + o.surface};
  }
};

// The sum of the per-particle inflows of one block of kBlock particles, in index order: the
// engine then adds the blocks in order (AddPoreWaterBlocks), so that the account does not depend
// on how the particles were split among threads (Determinism tests).
template <typename Real>
struct PoreWaterInflowBlockSum {
  static constexpr std::uint32_t kBlock = 256;
  const PoreWaterInflow<Real>* inflow;
  std::uint32_t begin, end;  // the soil particles

  CASCADE_HD PoreWaterInflow<Real> operator()(std::uint32_t block) const {
    PoreWaterInflow<Real> sum{Real(0), Real(0), Real(0)};
    const std::uint32_t first = begin + block * kBlock;
    const std::uint32_t last = end - first < kBlock ? end : first + kBlock;
    for (std::uint32_t i = first; i < last; ++i) sum = sum + inflow[i];
    return sum;
  }
};

// Adds the block sums, in order, times the step to the running totals (rain, walls, surface),
// which stay where the particles are: a step copies nothing back to the host. One thread.
template <typename Real>
struct AddPoreWaterBlocks {
  const PoreWaterInflow<Real>* blocks;
  std::uint32_t count;
  double dt;
  double* totals;

  CASCADE_HD void operator()(std::uint32_t) const {
    for (std::uint32_t k = 0; k < count; ++k) {
      totals[0] += dt * double(blocks[k].rain);
      totals[1] += dt * double(blocks[k].walls);
      totals[2] += dt * double(blocks[k].surface);
    }
  }
};

}  // namespace cascade
