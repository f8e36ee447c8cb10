// Dry granular column collapse (cases/column_collapse_2d.yaml: Drucker–Prager, c = 0, φ = 30°,
// ψ = 0, against a wall on a no-slip floor): the run-out at rest against the planar scaling law of
// Lube et al. (2005), (L∞ − L0)/L0 = 1.2 a for a = H0/L0 < 1.8 (tests/reference/column_collapse.h),
// at two aspect ratios, a = 0.5 and a = 1, with L0 = 0.1 m at dp = 0.005 m (20 particles across).
//
// Tolerance: 15% of 1.2 a at each aspect ratio. Lube et al.'s own scatter was not available
// (column_collapse.h); the fit is one line through sand, rice, sugar and couscous on rough and
// smooth floors, and Balmforth & Kerswell (2005) give the exponent of the same law as 0.9 ± 0.1,
// which alone spans ±7% at a = 0.5 about a line fitted near a = 1. Continuum SPH studies with
// Drucker–Prager or Coulomb-type models report their run-outs within 10–15% of these fits. A
// tighter bound would test which side of the experimental spread this model falls on, not the
// model. The measured values (docs/cases.md) are 9% (a = 0.5) and 12% (a = 1) short.
// The ratio of the two run-outs is tested as well: the law is linear in a, and its exponent,
// log2 of the ratio, must lie within Balmforth & Kerswell's 0.9 ± 0.1 widened to [0.8, 1.1]
// (Lube's linear branch is 1).
// Without the case's viscosity_switch (the compression switch on the soil's artificial viscosity,
// soil_viscosity_switch.h) the run-outs are 0.47 and 0.93, 22% short: this test fails on them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/reference/column_collapse.h"
#include "tests/validation/case_run.h"

namespace cascade {
namespace {

constexpr double kDp = 0.005, kL0 = 0.1;
constexpr double kRelativeTolerance = 0.15;

struct Collapse {
  double runout;   // (L∞ − L0)/L0, with the edge of the front particle (its centre + dp/2)
  double speed;    // the largest soil speed at the end [m/s]
  double time;     // when it came to rest [s]
};

// Runs the column of aspect ratio a until it is at rest: after the collapse time 3 sqrt(H0/g), the
// soil's largest speed below 1% of the free-fall speed sqrt(2 g H0), checked every 0.01 s.
Collapse collapse(double aspect_ratio) {
  const double h0 = aspect_ratio * kL0, g = 9.81;
  char box[64];
  std::snprintf(box, sizeof box, "bodies[2].shape.box.max=[%g, %g]", kL0, h0);
  testing::CaseRun run("column_collapse_2d.yaml", {"dp=" + std::to_string(kDp), box});
  const double earliest = 3 * std::sqrt(h0 / g), at_rest = 0.01 * std::sqrt(2 * g * h0), latest = 1.5;
  Collapse c{};
  for (double t = 0.01;; t += 0.01) {
    run.run_until(t);
    const FieldFrame frame = run.engine->frame();
    double front = 0, speed = 0;
    const FieldFrame::RealField* velocity = frame.find("velocity");
    for (std::size_t i = 0; i < frame.size(); ++i) {
      if (frame.phase[i] != 1) continue;
      front = std::max(front, frame.position[3 * i]);
      double v2 = 0;
      for (int a = 0; a < velocity->components; ++a) v2 += std::pow(velocity->values[i * velocity->components + a], 2);
      speed = std::max(speed, std::sqrt(v2));
    }
    c = {(front + kDp / 2 - kL0) / kL0, speed, run.engine->time()};
    if ((t >= earliest && speed < at_rest) || t >= latest) break;
  }
  EXPECT_EQ(run.engine->lost_particles(), 0u);
  EXPECT_LT(c.speed, at_rest) << "a = " << aspect_ratio << ": not at rest by t = " << c.time << " s";
  return c;
}

TEST(ColumnCollapse2D, RunoutAgainstLube2005AtTwoAspectRatios) {
  const double aspect[2] = {0.5, 1.0};
  double runout[2];
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(reference::collapse_regime(aspect[k]), reference::CollapseRegime::linear);
    const Collapse c = collapse(aspect[k]);
    const double expected = reference::lube2005_linear_runout(aspect[k]);
    std::printf("a = %.2f: ΔL/L0 = %.3f at rest at t = %.2f s; Lube et al. (2005) 1.2 a = %.3f (%+.1f%%)\n",
                aspect[k], c.runout, c.time, expected, 100 * (c.runout / expected - 1));
    EXPECT_NEAR(c.runout, expected, kRelativeTolerance * expected) << "a = " << aspect[k];
    runout[k] = c.runout;
  }
  const double exponent = std::log(runout[1] / runout[0]) / std::log(aspect[1] / aspect[0]);
  std::printf("run-out exponent between a = 0.5 and 1: %.3f (Lube 1, Balmforth & Kerswell 0.9 ± 0.1)\n", exponent);
  EXPECT_GE(exponent, 0.8);
  EXPECT_LE(exponent, 1.1);
}

}  // namespace
}  // namespace cascade
