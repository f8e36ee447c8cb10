// A drained wall: a solid boundary whose dummy particles carry a prescribed pore pressure on
// their soil side (Section 3.3.2.1, Eqs. 36, 37), e.g. p_w = 0 at the open base of the
// Liakopoulos column (Section 4.2), in place of the impermeable wall of Eqs. 32b and 35b.
//  - Eq. 36b: ρ_w,pres = ρ_w0 (1 + p_w,pres/K_w); Eq. 36a: ρ_w,b = 2 ρ_w,pres − ρ_w,g, with ρ_w,g
//    the value interpolated at the ghost node (Eq. 30, or Eq. 33b). The dummy and its ghost node
//    lie mirrored about the wall, so the prescribed value holds on the wall itself. The soil side
//    of a dummy stores p_w, not ρ_w (solid_boundary_soil.h); through the linear state of Eq. 6,
//    p_w = K_w/ρ_w0 (ρ_w − ρ_w0), Eq. 36a reads p_w,b = 2 p_w,pres − p_w,g for every K_w, which is
//    what is computed.
//  - Eq. 37 (q_w,b = q_w,g) is not needed: the dummy joins the soil's pairwise Darcy exchange with
//    this pressure (seepage_exchange.h), and water passes through the wall.
#pragma once

#include "server/core/types.h"

namespace cascade {

// Eqs. 36a, 36b in pressure form (above): the pore pressure the dummy shows its soil neighbours.
template <typename Real>
CASCADE_HD inline Real drained_wall_pore_pressure(Real prescribed_pressure, Real ghost_pressure) {
  return Real(2) * prescribed_pressure - ghost_pressure;
}

}  // namespace cascade
