// The 1995 Fei Tsui Road landslide (cases/fei_tsui_road_2d.yaml, paper Section 4.3, Table 2): a
// cut slope of altered tuff on a solid bed of decomposed tuff, at 50 kPa initial suction, under a
// rain heavy enough to pond its surface at p_w = 0 (Eq. 39). It must fail after its surface has
// ponded, not without the rain, and run out as far as observed: 29 m (Knill 1996).
//
// Runout, as the field measures it for a cut-slope failure: the horizontal distance from the toe
// of the original slope (x = 0 in the case) to the farthest tip of the deposit. The tip is the
// edge (centre + dp/2) of the farthest soil particle that belongs to the deposit, i.e. has at least
// three soil neighbours within the kernel support 2h: a lone particle thrown ahead of the debris
// is not a deposit (the case's `runout` probe reports the raw largest x; both are printed).
//
// The coarse run and its accelerations (each justified in the case file's header):
//  - dp = 0.5 m instead of the paper's 0.1 m (800 soil particles; the layer 8 to 13 across);
//  - K_sat = 0.1 m/s instead of Table 2's 1e-3 m/s (×100; the paper's own value is already an
//    acceleration, following Liu et al. 2020), the rain scaled with it (10 K_sat, which ponds the
//    surface within the first second: the paper's prescribed p_w = 0 of extreme rainfall). The
//    seepage time scales as 1/K_sat, so the ×100 brings the failure from about half an hour to
//    seconds; at ×100 the step is set by both the seepage limit of Eq. 40c and the P-wave speed,
//    so neither a larger K_sat nor a smaller E would buy more;
//  - E stays at Table 2's 50 MPa. (E = 10 MPa gave the same onset within 0.5 s and a tip 1.3 m
//    farther, docs/cases.md.)
// Measured (docs/validation.md): ponding within the first second, onset at 6 s, no onset without
// rain, the deposit's tip 12.4 m past the toe at rest (t = 33 s): 57% short of the 29 m (9.1 m
// before the kernel gradient was normalised on the lattice, docs/physics.md "Lattice moment"). The runout check is
// therefore a known failure (RunoutAgainstKnillKnownFailure, not loosened): the section of Fig. 11 is lost and the assumed
// one governs the runout (a first draft gave 16.6 m), while neither the ×100 K_sat (×10: 8.9 m)
// nor the coarse dp (0.35 m: 8.7 m) moves it. The check of the issue, |runout − 29 m| ≤ 25%, waits
// for the real section. No soil may leave through the decomposed tuff or get deeper than dp/2
// into it (before the impenetrable walls of docs/physics.md, 3 of 802 left).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "server/scenario/cascade_events.h"
#include "tests/validation/case_run.h"
#include "tests/validation/solid_depth.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

constexpr double kObservedRunout = 29.0;    // m, Knill (1996), as the paper quotes it
constexpr double kRelativeTolerance = 0.25;
constexpr double kToe = 0.0;                // x of the original slope toe in the case file
constexpr double kDp = 0.5;
constexpr std::uint8_t kSoil = 1;
const std::string kCase =
    "Fei Tsui Road landslide 2D, a demonstration, not a validation: its section is assumed, the paper's Fig. 11 "
    "being lost (cases/fei_tsui_road_2d.yaml)";

const std::vector<std::string> kCoarse = {"dp=0.5", "materials[0].soil.saturated_conductivity=0.1",
                                          "hydraulics.rainfall_intensity=1.0"};

struct Tip {
  double deposit;  // the edge of the farthest soil particle with >= 3 soil neighbours within 2h
  double raw;      // the edge of the farthest soil particle
};

Tip tip_of(const FieldFrame& frame, double h) {
  std::vector<std::size_t> soil;
  for (std::size_t i = 0; i < frame.size(); ++i)
    if (frame.phase[i] == kSoil) soil.push_back(i);
  Tip tip{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const double support2 = 4 * h * h;
  for (std::size_t i : soil) {
    const double xi = frame.position[3 * i], zi = frame.position[3 * i + 2];
    tip.raw = std::max(tip.raw, xi + kDp / 2);
    if (xi + kDp / 2 <= tip.deposit) continue;
    int neighbours = 0;
    for (std::size_t j : soil) {
      if (j == i) continue;
      const double dx = frame.position[3 * j] - xi, dz = frame.position[3 * j + 2] - zi;
      if (dx * dx + dz * dz < support2 && ++neighbours >= 3) break;
    }
    if (neighbours >= 3) tip.deposit = xi + kDp / 2;
  }
  return tip;
}

struct Outcome {
  double ponding = -1, onset = -1;  // event times (s); -1: did not fire
  double end = 0;                   // simulated time reached (s)
  Tip tip{};                        // at the end
  bool at_rest = false;
  std::size_t lost = 0, soil = 0;  // soil: all soil particles, lost ones included
  testing::SolidDepth::Count inside{};  // the most particles deeper than dp/2 in the tuff, any sample
  double half_spacing = 0;              // dp/2
};

// Runs the coarse case, sampling the events at the case's probe interval (as `cascade run` does).
// With rain: until the deposit's tip has moved less than 0.05 m over 3 s after the onset, or 60 s.
// Without (the control): for `duration`.
Outcome simulate(bool rain, double duration) {
  std::vector<std::string> overrides = kCoarse;
  if (!rain) overrides.push_back("hydraulics.rainfall_intensity=0");
  testing::CaseRun run("fei_tsui_road_2d.yaml", overrides);
  CascadeEventDetector events(run.spec, run.config.h, {});
  const testing::SolidDepth solids(run.spec);
  const double interval = run.spec.output().probe_interval(), rest_window = 3.0;
  Outcome o;
  std::vector<double> tips;  // the deposit's tip at each sample
  for (int k = 1;; ++k) {
    run.run_until(k * interval);
    const FieldFrame frame = run.engine->frame();
    for (const CascadeEvent& e : events.observe(frame, {}, run.spec.hydraulics().ponding_pressure())) {
      std::printf("%s at t = %.2f s: %s\n", e.kind.c_str(), run.engine->time(), e.message.c_str());
      if (e.kind == "ponding_started") o.ponding = run.engine->time();
      if (e.kind == "landslide_onset") o.onset = run.engine->time();
    }
    o.tip = tip_of(frame, run.config.h);
    o.end = run.engine->time();
    o.half_spacing = 0.5 * run.config.dp;
    o.inside.keep_worst(solids.inside(frame, o.half_spacing));
    tips.push_back(o.tip.deposit);
    if (!rain) {
      if (o.end >= duration) break;
      continue;
    }
    const int window = int(std::lround(rest_window / interval));
    if (o.onset >= 0 && int(tips.size()) > window && o.end > o.onset + rest_window &&
        std::fabs(tips.back() - tips[tips.size() - 1 - window]) < 0.05) {
      o.at_rest = true;
      break;
    }
    if (o.end >= duration) break;
  }
  o.lost = run.engine->lost_particles();
  for (std::uint8_t phase : run.engine->frame().phase) o.soil += phase == kSoil;
  std::printf("%s: t = %.2f s, ponding %.2f s, onset %.2f s, deposit tip %.2f m (raw %.2f m) from the toe%s, "
              "%zu of %zu soil particles lost\n",
              rain ? "rain" : "no rain", o.end, o.ponding, o.onset, o.tip.deposit - kToe, o.tip.raw - kToe,
              o.at_rest ? " at rest" : "", o.lost, o.soil);
  return o;
}

const Outcome& with_rain() {
  static const Outcome o = simulate(true, 60.0);
  return o;
}

TEST(FeiTsuiRoad2D, FailsAfterPondingNotWithoutRain) {
  const Outcome& wet = with_rain();
  ASSERT_GE(wet.ponding, 0) << "the surface never ponded";
  ASSERT_GE(wet.onset, 0) << "no landslide onset by t = " << wet.end << " s";
  EXPECT_LT(wet.ponding, wet.onset) << "the slope failed before its surface ponded";
  EXPECT_TRUE(wet.at_rest) << "the deposit still moving at t = " << wet.end << " s";
  EXPECT_GT(wet.tip.deposit - kToe, 0.0) << "the debris did not pass the toe";
  // The control: the same slope without rain, over 1.5 times the time the rain took to fail it.
  const Outcome dry = simulate(false, 1.5 * wet.onset);
  EXPECT_LT(dry.onset, 0) << "the slope failed without rain at t = " << dry.onset << " s";
  // The decomposed tuff, a solid boundary (Section 4.3), holds the debris: none leaves through it
  // and none gets into it (docs/physics.md, "Impenetrable walls"; before them 3 of 802 soil
  // particles went through, one 12 m deep at 46 m/s).
  char metric[64];
  std::snprintf(metric, sizeof metric, "soil particles that left the domain (of %zu)", wet.soil);
  CASCADE_VALIDATE({.case_name = kCase,
                    .reference = "the decomposed tuff, a solid boundary (paper Section 4.3): no soil leaves through it",
                    .metric = metric, .measured = double(wet.lost),
                    .reference_value = 0, .bound = testing::Bound::at_most, .tolerance_source = "exact"});
  testing::validate_outside_solids(kCase, wet.inside, wet.half_spacing, "at the probe samples");
}

// Known failure (the header says why: the assumed section governs the runout): the deposit's tip
// against Knill's (1996) 29 m, within the 25%. Measured 12.4 m (−57%).
TEST(FeiTsuiRoad2D, RunoutAgainstKnillKnownFailure) {
  const Outcome& wet = with_rain();
  ASSERT_TRUE(wet.at_rest) << "the deposit still moving at t = " << wet.end << " s";
  CASCADE_VALIDATE({.case_name = kCase, .reference = "Knill (1996), as the paper quotes it: observed runout 29 m",
                    .metric = "deposit tip from the original toe at rest, dp 0.5 m, K_sat × 100 [m]",
                    .measured = wet.tip.deposit - kToe, .reference_value = kObservedRunout,
                    .tolerance = kRelativeTolerance, .relative = true,
                    .tolerance_source = "the band the issue asks (|runout − 29 m| ≤ 25%), no stated source"});
}

}  // namespace
}  // namespace cascade
