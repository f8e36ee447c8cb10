// Variable time step (Eq. 40d): Δt = C0 min_i(Δt_cv, Δt_f), the per-particle limits written by the
// interaction pass (Eqs. 40a, 40b). The seepage limit (Eq. 40c) joins with the soil phase. A
// particle whose rates are not finite writes a negative limit, so the minimum is negative.
#pragma once

#include <cstdint>
#include <limits>

#include "server/core/types.h"

namespace cascade {

template <typename Real>
struct StepLimitOf {
  const Phase* phase;
  const Real* step_limit;
  CASCADE_HD Real operator()(std::uint32_t i) const {
    return phase[i] == Phase::boundary ? std::numeric_limits<Real>::max() : step_limit[i];
  }
};

template <typename Real>
struct MinimumOf {
  CASCADE_HD Real operator()(Real a, Real b) const { return a < b ? a : b; }
};

}  // namespace cascade
