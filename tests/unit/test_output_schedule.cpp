// When outputs repeating every `interval` are next due (server/scenario/output_schedule.h).
#include <gtest/gtest.h>

#include <cmath>

#include "server/scenario/output_schedule.h"

namespace cascade {
namespace {

// Ordinary intervals: the time of the plain loop `while (next <= t + slack) next += interval`,
// to the bit, so that runs keep their output times.
TEST(OutputSchedule, OrdinaryIntervalsGiveThePlainLoopsTimes) {
  int checked = 0;
  for (double interval : {0.05, 0.1, 1.0, 1800.0})
    for (double t : {0.0, 0.049999, 0.05, 0.3, 7.25, 3600.0}) {
      double loop = 0.05;
      while (loop <= t + 1e-12 * interval) loop += interval;
      if (loop - 0.05 > 60 * interval) continue;  // beyond the additions kept (the closed form)
      EXPECT_EQ(next_due_time(0.05, t, interval), loop) << "interval " << interval << ", t " << t;
      ++checked;
    }
  EXPECT_EQ(checked, 19);
}

// A step much longer than the interval: the next time after t, on the interval's grid, in one step.
TEST(OutputSchedule, ManyIntervalsInOneStepLandOnTheGrid) {
  const double next = next_due_time(0.0, 100.0, 1e-6);
  EXPECT_GT(next, 100.0);
  EXPECT_LE(next, 100.0 + 1e-6 * (1 + 1e-9));
  EXPECT_NEAR(std::remainder(next, 1e-6), 0.0, 1e-9);
}

// An interval lost in t's rounding (1e-300 s, a denormal, 0): due again just after t, never stuck
// at or before t, never at infinity.
TEST(OutputSchedule, IntervalsBelowTheRoundingOfTAreDueAtTheNextStep) {
  for (double interval : {1e-300, 4.9e-324, 1e-20, 0.0, -1.0}) {
    const double next = next_due_time(0.0, 600.0, interval);
    EXPECT_GT(next, 600.0) << interval;
    EXPECT_TRUE(std::isfinite(next)) << interval;
    EXPECT_LT(next, 600.0 + 1e-9) << interval;
  }
}

// Not yet due: unchanged.
TEST(OutputSchedule, NotYetDueIsUnchanged) { EXPECT_EQ(next_due_time(5.0, 4.0, 1.0), 5.0); }

}  // namespace
}  // namespace cascade
