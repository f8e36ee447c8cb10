// Issue 13, item 5: a smooth pore-pressure field. The particle-to-particle noise of p_w below 2%
// of the field's range over the soil, in the infiltration column (paper Section 4.1), the
// Liakopoulos column (Section 4.2), the infiltration column seeded laterally, and the storm demo's
// and the accelerated demo's slopes, by two measures: the largest residual of a local linear fit
// (soil_profiles.h: pore_pressure_noise), which also reads a resolved curvature as noise (the
// demos' known failures), and the amplitude of the odd-even mode by fourth differences along the
// lattice (odd_even_mode.h), which a field up to cubic does not reach.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "tests/validation/case_run.h"
#include "tests/validation/liakopoulos_case.h"
#include "tests/validation/odd_even_mode.h"
#include "tests/validation/soil_profiles.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

void validate_smooth(const testing::CaseRun& run, const std::string& case_name, const std::string& when) {
  const FieldFrame frame = run.engine->frame();
  const auto noise = testing::pore_pressure_noise(frame, run.config.h, run.config.dimensions);
  const auto soil = std::count(frame.phase.begin(), frame.phase.end(), std::uint8_t(Phase::soil));
  EXPECT_GT(soil, 0);
  EXPECT_EQ(noise.particles, std::size_t(soil));  // every soil particle fitted
  CASCADE_VALIDATE({.case_name = case_name,
                    .reference = "a smooth pore-pressure field: no particle-to-particle noise (issue 13, item 5)",
                    .metric = "largest |p_w − linear fit of its neighbours within 2h| / (max − min p_w), " + when,
                    .measured = noise.largest / noise.range, .reference_value = 0.02,
                    .bound = testing::Bound::at_most, .tolerance_source = "issue 13's bound: 2% of the field's range"});
}

// The odd-even mode's amplitude (odd_even_mode.h) against 2% of the range, on at least half the
// soil's particles.
void validate_odd_even(const testing::CaseRun& run, const std::string& case_name, const std::string& when) {
  const auto mode = testing::odd_even_mode(run.engine->frame(), "pore_pressure", run.config.dp);
  EXPECT_GT(mode.particles, 0u);
  EXPECT_GE(2 * mode.measured, mode.particles) << mode.measured << " of " << mode.particles << " measured";
  CASCADE_VALIDATE({.case_name = case_name,
                    .reference = "a smooth pore-pressure field: no odd-even mode on the lattice (issue 13, item 5)",
                    .metric = "largest |δ⁴p_w|/16 along a lattice axis / (max − min p_w), " + when,
                    .measured = mode.largest / mode.range, .reference_value = 0.02,
                    .bound = testing::Bound::at_most, .tolerance_source = "issue 13's bound: 2% of the field's range"});
}

// The measure itself: 0 for a cubic field on a 24 × 24 lattice, and a checkerboard of amplitude A
// added to it read as A, wherever the lattice is (an offset origin) and with its particles crept
// from it by a smooth displacement of up to dp/5.
TEST(PorePressureNoise, OddEvenMeasureSeesTheModeAndNotACubic) {
  constexpr int kSide = 24;
  constexpr double kDp = 0.1, kAmplitude = 3.0;
  FieldFrame f;
  f.dimensions = 2;
  FieldFrame::RealField smooth{"smooth", "Pa", 1, {}}, checkered{"checkered", "Pa", 1, {}};
  for (int a = 0; a < kSide; ++a)
    for (int b = 0; b < kSide; ++b) {
      const double creep = 0.2 * kDp * std::sin(0.3 * a + 0.2 * b);
      const double x = 0.37 + a * kDp + creep, z = -1.21 + b * kDp - creep;
      f.position.insert(f.position.end(), {x, 0.0, z});
      f.phase.push_back(std::uint8_t(Phase::soil));
      f.id.push_back(std::uint32_t(f.id.size()));
      // A cubic of the lattice coordinates (the fourth difference takes the particles as on it).
      const double u = a * kDp, w = b * kDp;
      const double cubic = 1e3 * (1 + 2 * u - 3 * w + u * u - 4 * u * w + 2 * u * u * u - w * w * w + u * u * w);
      smooth.values.push_back(cubic);
      checkered.values.push_back(cubic + ((a + b) % 2 ? kAmplitude : -kAmplitude));
    }
  f.fields = {smooth, checkered};
  const auto flat = testing::odd_even_mode(f, "smooth", kDp);
  const auto mode = testing::odd_even_mode(f, "checkered", kDp);
  EXPECT_EQ(flat.particles, std::size_t(kSide * kSide));
  EXPECT_EQ(flat.measured, std::size_t(kSide * kSide - 4 * 4));  // all but the 2 × 2 corners' blocks
  EXPECT_LT(flat.largest, 1e-9 * flat.range);
  EXPECT_NEAR(mode.largest, kAmplitude, 1e-9 * mode.range);
}

TEST(PorePressureNoise, InfiltrationColumn) {
  testing::CaseRun run("infiltration_1d.yaml");
  const std::string name = "1D infiltration (cases/infiltration_1d.yaml)";
  for (double day : {0.05, 0.25}) {
    run.run_until(day * 86400.0);
    validate_smooth(run, name, "t = " + std::to_string(day).substr(0, 4) + " day");
    validate_odd_even(run, name, "t = " + std::to_string(day).substr(0, 4) + " day");
  }
}

// The same column seeded with a lateral perturbation of round-off size (its periodic width 1e-10 m
// longer), to 0.3 day (on to the case's end at 0.5 day the base nears saturation, the step falls
// towards Eq. 40c's 0.02 s of saturated soil, and the run took 500 s). A periodic column is
// laterally uniform, so the largest spread of p_w within one particle layer is the measure,
// exactly 0 in the analytic solution. With the divergence of the renormalised gradient (before
// 2026-12-06) an odd-even mode in the second layer below the flux-condition surface grew from the
// seed some 300 times every 0.05 day (2e-6 Pa at 0.05 day, 1e4 Pa at 0.25 day, the run breaking
// down past 0.4 day); the pairwise Darcy exchange damps every mode (docs/physics.md, "Smoothness of
// the pore pressure").
TEST(PorePressureNoise, InfiltrationColumnSeeded) {
  testing::CaseRun run("infiltration_1d.yaml", {"domain.max=[0.2400000001,3.1]"});
  run.run_until(0.3 * 86400.0);
  const FieldFrame f = run.engine->frame();
  EXPECT_EQ(testing::layer_pressures(f).size(), 150u);  // 150 layers of 12 particles
  const auto noise = testing::pore_pressure_noise(f, run.config.h, run.config.dimensions);  // for its range
  EXPECT_EQ(noise.particles, 1800u);
  const double spread = testing::largest_layer_pressure_spread(f);
  CASCADE_VALIDATE({.case_name = "1D infiltration seeded laterally (cases/infiltration_1d.yaml, periodic width + 1e-10 m)",
                    .reference = "a laterally uniform column: p_w the same across every layer (issue 13, item 5)",
                    .metric = "largest spread of p_w within a layer / (max − min p_w), t = 0.3 day",
                    .measured = spread / noise.range, .reference_value = 0.02,
                    .bound = testing::Bound::at_most, .tolerance_source = "issue 13's bound: 2% of the field's range"});
}

TEST(PorePressureNoise, LiakopoulosColumn) {
  constexpr double kAlpha = 100.0;
  testing::CaseRun run("liakopoulos.yaml", testing::accelerated_liakopoulos(kAlpha));
  const std::string name = "Liakopoulos drainage (cases/liakopoulos.yaml, dp = 0.05 m, K_sat × 100)";
  for (double t : {300.0, 1200.0}) {
    run.run_until(t / kAlpha);
    validate_smooth(run, name, "t = " + std::to_string(int(t)) + " s");
    validate_odd_even(run, name, "t = " + std::to_string(int(t)) + " s");
  }
}

// Known failure: the README's main job (cases/cascade_storm_2d.yaml), the same slope at its real
// K_sat under the storm, its rain stage on the implicit pore-water step, at 1 h and 3 h of rain (the
// failure comes at about 4.3 h). Measured when written: 12.8% and 7.9% of the range. The field is
// smooth there but curved: the largest residual is the top particle of the toe's vertical face,
// where the wetting front from the slope meets it (p_w −5084, −5624, −6041 Pa down the face, a
// second difference of 123 Pa, and the one-sided fit's residual 247 Pa), and down the column at
// x = 2.05 m the residual keeps one sign over seven particles (the front's curvature, which a
// linear fit reads as −p''⟨r²⟩/2), not the odd-even alternation of the explicit demo below. The
// staircase of the 40° surface (two particles on a tread every sixth column) alternates by some
// 30 Pa (1.5%). The noise measure has to separate resolved curvature from particle noise before
// this figure says which it is (issue 13, item 5). The odd-even mode's amplitude by fourth
// differences (odd_even_mode.h), blind to curvature, measured 3.0% and 1.6% when added
// (2026-12-06), the largest along x at (2.75, 2.55) m, a row whose five particles run from inside
// the slope to its 40° face, across the wetting front below the face: a front a few particles
// wide has a fourth difference of its own, so the 3.0% at 1 h is not yet shown to be a mode.
TEST(PorePressureNoise, StormDemoRainStageKnownFailure) {
  testing::CaseRun run("cascade_storm_2d.yaml");
  const std::string name = "Storm cascade demo, rain stage (cases/cascade_storm_2d.yaml)";
  for (double hours : {1.0, 3.0}) {
    run.run_until(hours * 3600.0);
    ASSERT_EQ(run.engine->stage(), 1) << "still raining on the standing slope";
    validate_smooth(run, name, "t = " + std::to_string(int(hours)) + " h");
    validate_odd_even(run, name, "t = " + std::to_string(int(hours)) + " h");
  }
}

// The accelerated demo's slope under rain (issue 13: its pore-pressure snapshots show the
// checkerboard), on the explicit step.
// Measured when written: 55%, 47% and 68% of the range at 2, 5 and 10 s, the largest residuals on
// the slope's surface, whose particles alternate by some 300 Pa.
// By the odd-even mode's amplitude (added 2026-12-06): 11.1%, 2.3% and 2.04% at 2, 5 and 10 s, the
// largest along x at (1.45, 3.65) m, a row running from inside the slope to its face where the
// rain's front is a particle or two deep at 2 s, and at 10 s along z at (0.05, 3.75) m, the column
// of the free face at x = 0 that the front descends. At dp = 0.05 m (development run, 2026-12-06)
// both figures fall: odd-even 2.4%, 1.24%, 0.82%, linear fit 14.8%, 7.7%, 5.9%: what they read
// falls with resolution, as the footprint of an under-resolved front does.
TEST(PorePressureNoise, CascadeDemoKnownFailure) {
  testing::CaseRun run("cascade_demo_2d.yaml");
  const std::string name = "Cascade demo 2D (cases/cascade_demo_2d.yaml)";
  for (double t : {2.0, 5.0, 10.0}) {
    run.run_until(t);
    validate_smooth(run, name, "t = " + std::to_string(int(t)) + " s");
    validate_odd_even(run, name, "t = " + std::to_string(int(t)) + " s");
  }
}

}  // namespace
}  // namespace cascade
