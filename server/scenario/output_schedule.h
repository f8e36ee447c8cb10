// When an output that repeats every `interval` of simulated time (frames, probe samples, watch
// frames) is next due, after it was taken at time t.
#pragma once

#include <cmath>
#include <limits>

namespace cascade {

// The first time next + k·interval (k ≥ 0) after t + 1e-12·interval, found in one step: an
// interval far below the step (1e-300 s, or below t's rounding) would take the plain loop
// `while (next <= t) next += interval` forever, in the solver thread and under its lock, which froze
// every request of the server. The few additions of an ordinary step are kept, so that the
// schedule of existing runs is the same to the bit; where the interval is lost in t's rounding the
// output is due again at the next step (at most one output per step).
inline double next_due_time(double next, double t, double interval) {
  const double after_t = std::nextafter(t, std::numeric_limits<double>::infinity());
  if (!(interval > 0)) return after_t;
  const double slack = 1e-12 * interval;
  for (int k = 0; k < 64 && next <= t + slack; ++k) next += interval;
  if (next <= t + slack) {
    const double missed = std::floor((t + slack - next) / interval) + 1;  // intervals that fit in the step
    next = std::isfinite(missed) ? next + missed * interval : after_t;
  }
  return next > t && std::isfinite(next) ? next : after_t;
}

}  // namespace cascade
