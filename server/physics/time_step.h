// Variable time step (Eq. 40d): Δt = C0 min_i(Δt_cv, Δt_f), the per-particle limits written by the
// interaction pass (Eqs. 40a, 40b). The seepage limit (Eq. 40c) joins with the soil phase. A
// particle whose rates are not finite writes a negative limit, so the minimum is negative. The
// minimum runs over the moving particles only, which the cell sort puts first.
#pragma once

#include <cstdint>
#include <limits>

#include "server/core/types.h"

namespace cascade {

template <typename Real>
struct MinimumOf {
  CASCADE_HD Real operator()(Real a, Real b) const { return a < b ? a : b; }
};

}  // namespace cascade
