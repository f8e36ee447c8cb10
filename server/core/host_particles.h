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
  std::vector<double> water_density;     // N, ρ_w (kg/m³): of the free water (its pressure through
                                         // Eq. 6 with K_w = ρ_w0 c_w0²) or, for a soil particle, of
                                         // its pore water (the soil material's K_w)
  std::vector<double> porosity;          // N: φ of a soil particle (Eq. 26a), 0 for other phases
  std::vector<std::uint8_t> soil_material;  // N: index into EngineConfig::soils (soil particles)
  std::vector<double> effective_stress;  // N × 6: σ' (Eq. 7) of a soil particle, Voigt xx, yy, zz,
                                         // xy, yz, zx, Pa, tension positive (2D: y out of plane);
                                         // zeros for other phases
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
