// 2D dam break (cases/dam_break_2d.yaml, a = 0.146 m, column 2a high): the surge front against the
// experiments of Martin & Moyce (1952, Phil. Trans. R. Soc. A 244, Table 2, n² = 2) and below
// Ritter's dry-bed solution, x_front = a + 2 sqrt(g H0) t with H0 = 2a, i.e. Z = 1 + 2T.
// Z = x_front / a, T = t sqrt(2g/a).
//
// Weakly compressible SPH leads the measured front by 10-20% at early times: the experiment's
// column was released by a gate that took time to clear, a delay the simulations do not have
// (Colagrossi & Landrini 2003, J. Comput. Phys. 191; Marrone et al. 2011, CMAME 200). Once the
// surge is established its speed agrees: the test checks the front speed over T = 1.4-3.0 within
// 10% and the position within 20%, before the front reaches the far wall (Z = 4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tests/validation/case_run.h"
#include "tests/validation/solid_depth.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

struct Point {
  double T, Z;
};

// Martin & Moyce (1952), Table 2, square-based column with n² = 2 (height 2a).
const std::vector<Point> kMartinMoyce = {{0.41, 1.11}, {0.84, 1.22}, {1.19, 1.44}, {1.43, 1.67}, {1.63, 1.89},
                                         {1.83, 2.11}, {1.98, 2.33}, {2.20, 2.56}, {2.32, 2.78}, {2.51, 3.00},
                                         {2.65, 3.22}, {2.83, 3.44}, {2.98, 3.67}};

double interpolate(const std::vector<Point>& curve, double T) {
  for (std::size_t k = 1; k < curve.size(); ++k)
    if (curve[k].T >= T) {
      const double s = (T - curve[k - 1].T) / (curve[k].T - curve[k - 1].T);
      return curve[k - 1].Z + s * (curve[k].Z - curve[k - 1].Z);
    }
  return curve.back().Z;
}

constexpr double kA = 0.146, kG = 9.81;
const double kTimeScale = std::sqrt(2 * kG / kA);  // T = t · time_scale

// The surge front Z(T) every 2 ms of simulated time to T = 3.05, with the case's overrides (dp).
std::vector<Point> surge_front(const std::vector<std::string>& overrides = {}) {
  testing::CaseRun run("dam_break_2d.yaml", overrides);
  std::vector<Point> simulated;
  const double end = 3.05 / kTimeScale;
  double next_sample = 0;
  while (run.engine->time() < end) {
    run.engine->step();
    if (run.engine->time() < next_sample) continue;
    next_sample += 0.002;
    const auto water = testing::water_values(run.engine->frame(), "pressure");
    const double front = *std::max_element(water.x.begin(), water.x.end());
    simulated.push_back({run.engine->time() * kTimeScale, front / kA});
  }
  EXPECT_EQ(run.engine->lost_particles(), 0u);
  return simulated;
}

TEST(DamBreak2D, SurgeFrontAgainstMartinMoyceAndBelowRitter) {
  const std::vector<Point> simulated = surge_front();

  // Below Ritter's ideal-fluid front at every sample after the first step.
  double largest_lead_over_ritter = -INFINITY;
  for (const auto& p : simulated)
    if (p.T > 0.05) largest_lead_over_ritter = testing::worst_of(largest_lead_over_ritter, p.Z - (1.0 + 2.0 * p.T));

  const std::string case_name = "2D dam break (cases/dam_break_2d.yaml)";
  const std::string reference = "Martin & Moyce (1952), Table 2, n² = 2";
  const std::string gate_delay =
      "the experiment's gate delay: WCSPH leads the measured front by 10-20% (Colagrossi & Landrini 2003)";
  std::size_t compared = 0;
  for (const auto& m : kMartinMoyce) {
    if (m.T < 0.8) continue;
    char metric[64];
    std::snprintf(metric, sizeof metric, "front position Z = x/a at T = %.2f", m.T);
    CASCADE_VALIDATE({.case_name = case_name, .reference = reference, .metric = metric,
                      .measured = interpolate(simulated, m.T), .reference_value = m.Z, .tolerance = 0.20,
                      .relative = true, .tolerance_source = gate_delay});
    ++compared;
  }
  EXPECT_EQ(compared, 12u);
  CASCADE_VALIDATE({.case_name = case_name, .reference = "Ritter's dry-bed solution, Z = 1 + 2T (an upper bound)",
                    .metric = "largest Z − (1 + 2T) over the samples after T = 0.05", .measured = largest_lead_over_ritter,
                    .reference_value = 0, .bound = testing::Bound::at_most,
                    .tolerance_source = "exact: no real fluid outruns the ideal one"});
  const double measured_speed = (interpolate(kMartinMoyce, 2.98) - interpolate(kMartinMoyce, 1.43)) / (2.98 - 1.43);
  const double simulated_speed = (interpolate(simulated, 2.98) - interpolate(simulated, 1.43)) / (2.98 - 1.43);
  CASCADE_VALIDATE({.case_name = case_name, .reference = reference, .metric = "front speed dZ/dT over T = 1.43-2.98",
                    .measured = simulated_speed, .reference_value = measured_speed, .tolerance = 0.10,
                    .relative = true,
                    .tolerance_source = "the scatter of WCSPH surge speeds against this experiment once the gate "
                                        "has cleared (Colagrossi & Landrini 2003; Marrone et al. 2011)"});
}

// Walls that hold (issue 13, item 1): the surge hits the far wall at T ≈ 3 (t ≈ 0.26 s), runs up
// it in a jet that rises past 0.8 m, falls back and rebounds towards the left wall by t = 0.8 s.
// At dp = a/20 (the test's budget) and h/dp 1.3 (the case's) and 1.5: no water particle centre
// deeper than dp/2 in the tank's walls at any 5 ms sample, and none lost through them. The tank is
// open: splash thrown over a wall's top (z = 0.45 m) leaves the domain beside the tank, as it
// would leave a real one (2 particles at h/dp 1.3 when written, over the left wall at z = 0.91 m);
// those are counted apart.
TEST(DamBreak2D, ImpactOnTheFarWallStaysOutside) {
  constexpr double kWallTop = 0.45;
  for (const char* h_over_dp : {"1.3", "1.5"}) {
    testing::CaseRun run("dam_break_2d.yaml", {"dp=0.0073", std::string("h_over_dp=") + h_over_dp});
    testing::WallWatch walls(run.spec);
    walls.sample(run.engine->frame());
    for (int k = 1; k <= 160; ++k) {
      run.run_until(0.005 * k);
      walls.sample(run.engine->frame());
    }
    const FieldFrame end = run.engine->frame();
    const FieldFrame::RealField* lost = end.find("lost");
    ASSERT_NE(lost, nullptr);
    std::size_t below_top = 0, over_top = 0;  // lost particles, where they left the domain
    for (std::size_t i = 0; i < end.size(); ++i)
      if (lost->values[i] != 0) ++(end.position[3 * i + 2] < kWallTop ? below_top : over_top);
    std::printf("h/dp = %s: %zu particles lost over the walls' top, %zu below it\n", h_over_dp, over_top, below_top);
    const std::string case_name = std::string("2D dam break (cases/dam_break_2d.yaml), dp = a/20, h/dp = ") + h_over_dp;
    CASCADE_VALIDATE({.case_name = case_name, .reference = "the tank's walls hold: nothing leaves below their top",
                      .metric = "particles lost below the walls' top (z < 0.45 m) by t = 0.8 s",
                      .measured = double(below_top), .reference_value = 0, .bound = testing::Bound::at_most,
                      .tolerance_source = "exact: a count"});
    walls.validate(case_name, "at the 5 ms samples to t = 0.8 s");
  }
}

// Issue 14, item 4: is the lead over the experiment resolution? The case at dp = a/20 and at its
// own a/40; with first-order convergence in dp (assumed: two resolutions cannot give the order)
// the front at dp → 0 is 2 Z(a/40) − Z(a/20) (Richardson), held to the same band as above.
// Measured when written: refining moves the front forward by 1-2.5%, and the extrapolated front
// leads Martin & Moyce by 21% at T = 1.19, just outside the band: the lead is the gate delay, not
// resolution, and slightly larger than 20% once converged.
TEST(DamBreak2D, ConvergedFrontAgainstMartinMoyceKnownFailure) {
  const std::vector<Point> coarse = surge_front({"dp=0.0073"});  // a/20
  const std::vector<Point> fine = surge_front();                  // a/40
  const std::string case_name = "2D dam break (cases/dam_break_2d.yaml), dp = a/20 and a/40";
  std::size_t compared = 0;
  for (const auto& m : kMartinMoyce) {
    if (m.T < 0.8) continue;
    const double z_fine = interpolate(fine, m.T), z_coarse = interpolate(coarse, m.T);
    char metric[96];
    std::snprintf(metric, sizeof metric, "front Z at T = %.2f extrapolated to dp → 0, 2 Z(a/40) − Z(a/20)", m.T);
    CASCADE_VALIDATE({.case_name = case_name, .reference = "Martin & Moyce (1952), Table 2, n² = 2", .metric = metric,
                      .measured = 2 * z_fine - z_coarse, .reference_value = m.Z, .tolerance = 0.20, .relative = true,
                      .tolerance_source = "the experiment's gate delay: WCSPH leads the measured front by 10-20% "
                                          "(Colagrossi & Landrini 2003)"});
    ++compared;
  }
  EXPECT_EQ(compared, 12u);
}

}  // namespace
}  // namespace cascade
