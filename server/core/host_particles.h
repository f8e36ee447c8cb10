// Initial particle set on the host, in double precision: what the scenario builder produces and
// the engine copies into its own arrays (converted to its precision, on its device).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "server/core/types.h"

namespace cascade {

struct HostParticles {
  int dimensions = 0;                    // 2 (x, z) or 3 (x, y, z)
  std::vector<double> position;          // N × dimensions
  std::vector<double> velocity;          // N × dimensions
  std::vector<double> water_density;     // N, ρ_w (kg/m³); gives the water pressure through Eq. 6
  std::vector<Phase> phase;              // N
  std::vector<double> ghost;             // N × dimensions: ghost node x_g of a boundary particle
                                         // (mirror of x_b across the nearest wetted surface); for
                                         // other phases a copy of the position
  std::vector<std::uint32_t> body;       // N: index of the Body in ScenarioSpec.bodies

  std::size_t size() const { return phase.size(); }
  std::size_t count(Phase p) const {
    std::size_t n = 0;
    for (Phase q : phase) n += (q == p);
    return n;
  }
};

}  // namespace cascade
