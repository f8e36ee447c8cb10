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
// soil_viscosity_switch.h) the run-outs were 0.47 and 0.93, 22% short: this test failed on them.
//
// Known failure since 2026-12-03 (README, "Known failures"). The run-outs above held because the
// column's residual pore water was as stiff as a saturated soil's: the flow's dilation drove the
// suction from 10 kPa to 700 kPa, and Bishop's stress (Eq. 7) gave the "dry" sand up to 600 Pa of
// apparent confinement (its mean effective pressure is about 400 Pa). With the residual water
// moving with the grains (docs/physics.md, "Grain-bound water") the suction stays at 10 kPa and the
// run-outs are 1.05 and 2.41 with the switch (1.68 at a = 1 without it, before the lattice normalisation): a dry granular flow of
// this model runs out far past Lube's law. Measured at a = 1: 20-30% of the moving particles carry
// no effective stress at all (at the Drucker-Prager apex, c = 0), so they flow without friction.
// Why they lose their stress is not traced yet (issue 13).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/reference/column_collapse.h"
#include "tests/validation/case_run.h"
#include "tests/validation/solid_depth.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

constexpr double kDp = 0.005, kL0 = 0.1;
constexpr double kRelativeTolerance = 0.15;
const std::string kCase = "Granular column collapse 2D (cases/column_collapse_2d.yaml)";

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
  testing::WallWatch walls(run.spec);  // issue 13, item 1
  walls.sample(run.engine->frame());
  for (double t = 0.01;; t += 0.01) {
    run.run_until(t);
    const FieldFrame frame = run.engine->frame();
    walls.sample(frame);
    double front = 0, speed = 0;
    const FieldFrame::RealField* velocity = frame.find("velocity");
    for (std::size_t i = 0; i < frame.size(); ++i) {
      if (frame.phase[i] != 1) continue;
      front = std::max(front, frame.position[3 * i]);
      double v2 = 0;
      for (int a = 0; a < velocity->components; ++a) v2 += std::pow(velocity->values[i * velocity->components + a], 2);
      speed = testing::worst_of(speed, std::sqrt(v2));
    }
    c = {(front + kDp / 2 - kL0) / kL0, speed, run.engine->time()};
    if ((t >= earliest && speed < at_rest) || t >= latest) break;
  }
  char metric[64];
  std::snprintf(metric, sizeof metric, "particles lost, a = %.1f", aspect_ratio);
  CASCADE_VALIDATE({.case_name = kCase, .reference = "mass conservation: no particle leaves the domain",
                    .metric = metric, .measured = double(run.engine->lost_particles()), .reference_value = 0,
                    .bound = testing::Bound::at_most, .tolerance_source = "exact"});
  std::snprintf(metric, sizeof metric, "a = %.1f, at the 10 ms samples", aspect_ratio);
  walls.validate(kCase, metric);
  EXPECT_LT(c.speed, at_rest) << "a = " << aspect_ratio << ": not at rest by t = " << c.time << " s";
  return c;
}

TEST(ColumnCollapse2D, RunoutAgainstLube2005AtTwoAspectRatiosKnownFailure) {
  const double aspect[2] = {0.5, 1.0};
  double runout[2];
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(reference::collapse_regime(aspect[k]), reference::CollapseRegime::linear);
    runout[k] = collapse(aspect[k]).runout;
    char metric[64];
    std::snprintf(metric, sizeof metric, "run-out ΔL/L0 at rest, a = %.1f", aspect[k]);
    CASCADE_VALIDATE({.case_name = kCase, .reference = "Lube et al. (2005), planar law ΔL/L0 = 1.2 a for a < 1.8",
                      .metric = metric, .measured = runout[k],
                      .reference_value = reference::lube2005_linear_runout(aspect[k]),
                      .tolerance = kRelativeTolerance, .relative = true,
                      .tolerance_source = "the law's spread: Balmforth & Kerswell (2005) give its exponent as "
                                          "0.9 ± 0.1 (±7% at a = 0.5), and continuum SPH studies (not cited) "
                                          "report 10-15%; Lube et al.'s own scatter not available"});
  }
  const double exponent = std::log(runout[1] / runout[0]) / std::log(aspect[1] / aspect[0]);
  const std::string reference = "Balmforth & Kerswell (2005), exponent 0.9 ± 0.1; Lube et al. (2005), 1";
  const std::string metric = "run-out exponent log2(ΔL(a = 1)/ΔL(a = 0.5))";
  const std::string widened = "Balmforth & Kerswell's 0.9 ± 0.1, widened above to 1.1 past Lube's 1 (no source "
                              "states the widening)";
  CASCADE_VALIDATE({.case_name = kCase, .reference = reference, .metric = metric, .measured = exponent,
                    .reference_value = 0.8, .bound = testing::Bound::at_least, .tolerance_source = widened});
  CASCADE_VALIDATE({.case_name = kCase, .reference = reference, .metric = metric, .measured = exponent,
                    .reference_value = 1.1, .bound = testing::Bound::at_most, .tolerance_source = widened});
}

}  // namespace
}  // namespace cascade
