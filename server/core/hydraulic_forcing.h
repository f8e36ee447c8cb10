// The hydraulic conditions on the free surface of the soil (Eq. 39): rainfall (or evaporation)
// flux, the ponding pressure p_max and the drying limit p_min. Run-time parameters of the solver:
// the runner or the steering server sets them between steps (Engine::set_forcing), and a change
// takes effect at the next step.
#pragma once

#include <array>
#include <limits>

namespace cascade {

struct HydraulicForcing {
  // Vertical flux into the soil at its free-surface particles (m/s): rainfall > 0, evaporation
  // < 0. The prescribed seepage discharge of such a particle is q_w = (0, ..., −intensity).
  double rainfall_intensity = 0;
  // p_max (Pa): a free-surface particle whose pore pressure reaches it ponds, and holds
  // p_w = p_max until the soil below takes more than the rain again.
  double ponding_pressure = 0;
  // p_min (Pa): a drying free-surface particle holds p_w = p_min once it reaches it.
  double drying_pressure = -std::numeric_limits<double>::infinity();
  // A pore pressure (Pa) held by every free-surface particle, with the seepage of Eq. 27b (a
  // Dirichlet condition of Eq. 39, e.g. the drained top of Section 4.2's initialisation stage);
  // the flux, ponding and drying conditions do not apply while it holds.
  bool has_surface_pressure = false;
  double surface_pressure = 0;
  // Rain falls on the free-surface particles inside this box only (the first `dimensions`
  // components, (x, z) in 2D); elsewhere the surface takes no flux.
  bool has_region = false;
  std::array<double, 3> region_min{};
  std::array<double, 3> region_max{};
};

}  // namespace cascade
