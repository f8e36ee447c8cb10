// Liakopoulos' drainage test (paper Section 4.2, cases/liakopoulos.yaml): the SPH pore-pressure
// profiles and the settlement of the top against the OpenGeoSys RICHARDS_MECHANICS profiles at
// t = 300, 600 and 7200 s after the start of drainage (tests/reference/liakopoulos_reference.h).
//
// Run time. At the case's K_sat = 4.41e-6 m/s the drainage takes hours of simulated time, while
// the step is set by the skeleton's P-wave speed (Eq. 40b, about 3.5e-4 s at dp = 0.05 m): 2e7
// steps to 7200 s. The test runs the accelerated seepage of the paper's Section 4.3 (Yerro et al.
// 2015; Bandara et al. 2016): K_sat and the initialisation stage scaled by α = 100 and 1/α, and
// the profiles compared at t/α. With a quasi-static skeleton the coupled equations (Eqs. 26a,
// 27a, 27b with a_s → 0) hold the time only in the product K t, so the solution at t/α is the
// one at t; the test checks that this holds here, by a second run with α = 50 that must agree
// with the first at 300 s within 1% of the top pressure (measured: under 1 Pa). The column is
// coarse, dp = 0.05 m (20 particles over the height, the paper has 50), 10 particles across the
// periodic width (6.3 h).
//
// Tolerance: every layer's mean p_w within 10% of |p_w| at the top of the reference profile, the
// top layer's settlement within 20% of OGS' at the same height. The differences the reference
// header lists, and their sizes here:
//  - K_w = 2e6 Pa (Table 1) against OGS' 2e9 Pa: the pore water stores φ/K_w = 1.5e-7 1/Pa,
//    against the skeleton's 1/M = 3.6e-7 1/Pa: a saturated zone drains about 40% slower, which
//    shows near the base, where the capillary storage vanishes;
//  - Eq. 43a with ρ_w0 g = 9810 Pa/m against OGS' 10^4 Pa/m: 5% more saturation deficit at a
//    given suction, a few per cent less suction for the same drained water;
//  - the SPH column: 20 particles, the odd-even modes of collocated SPH on the pore pressure
//    (about ±50 Pa between neighbouring layers after the initialisation), and about 100 Pa of
//    excess pore pressure that the 20 s initialisation leaves (its consolidation time is some
//    200 s: c_v = K_sat/(γ_w (1/M + φ/K_w)) ≈ 9e-4 m²/s over the 0.5 m drainage path);
//  - published solutions of the same test (Schrefler and Scotta 2001, Lewis and Schrefler 1998,
//    OGS, and the paper's own SPH against the measurements in Fig. 9) differ among themselves by
//    some 10% of the top suction in the first 10 minutes.
// The settlement has one more: the excess pore pressure left by the initialisation consolidates
// during the drainage and settles the column by about ∫Δp dz / M ≈ 100 Pa · 1 m / 2.8 MPa ≈ 4e-5 m
// more than OGS' column, which starts from p_w = 0: some 8% of the settlement at 300 s.
// Measured when the test was written (1 thread, 94 s): 3.7%, 1.9% and 0.7% of the top pressure at
// 300, 600 and 7200 s; the top layer's settlement 13.3%, 13.2% and 12.2% above OGS'; α = 50
// against α = 100 at 300 s: 0.18 Pa.
// Convergence (issue 14, item 4): the same case at dp = 0.1 m runs beside it; the top's settlement
// relative to OGS, 1.27 at dp 0.1 and 1.13 at dp 0.05 (at 300 s), extrapolates to dp → 0 as
// 1.00, 1.02 and 1.05 at the three times (measured when written): the +13% is resolution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tests/reference/liakopoulos_reference.h"
#include "tests/validation/case_run.h"
#include "tests/validation/solid_depth.h"
#include "tests/validation/liakopoulos_case.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

using Reference = reference::LiakopoulosOgsProfiles;

struct Layers {
  std::vector<double> z, pressure, settlement;
};

// Layer means of the soil particles' p_w and u_z, bottom to top.
Layers layers(const FieldFrame& f) {
  std::map<double, std::vector<double>> sums;  // z → {p, u_z, count}
  const auto* p = f.find("pore_pressure");
  const auto* u = f.find("displacement");
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.phase[i] != std::uint8_t(Phase::soil)) continue;
    auto& s = sums[std::round(f.position[3 * i + 2] * 1e3) / 1e3];
    s.resize(3, 0.0);
    s[0] += p->values[i], s[1] += u->values[3 * i + 2], s[2] += 1;
  }
  Layers out;
  for (const auto& [z, s] : sums) {
    out.z.push_back(z);
    out.pressure.push_back(s[0] / s[2]);
    out.settlement.push_back(s[1] / s[2]);
  }
  return out;
}

TEST(Liakopoulos, PorePressureProfilesAgainstOpenGeoSys) {
  constexpr double kAlpha = 100.0;
  const std::string case_name = "Liakopoulos drainage (cases/liakopoulos.yaml, dp = 0.05 m, K_sat × 100)";
  const std::string ogs = "OpenGeoSys RICHARDS_MECHANICS, LiakopoulosHM benchmark (W. Wang 2020; "
                          "tests/reference/liakopoulos_reference.h)";
  testing::CaseRun run("liakopoulos.yaml", testing::accelerated_liakopoulos(kAlpha));
  // Issue 14, item 4: the same case at dp = 0.1 m (1 m wide, so that the periodic axis spans 6h and
  // the skin; the base four layers deep), for the settlement's convergence below.
  auto coarse_overrides = testing::accelerated_liakopoulos(kAlpha);
  for (const char* o : {"dp=0.1", "domain.min=[0.0, -0.4]", "domain.max=[1.0, 1.1]", "bodies[0].shape.box.min=[0.0, -0.4]",
                        "bodies[0].shape.box.max=[1.0, 0.0]", "bodies[1].shape.box.max=[1.0, 1.0]"})
    coarse_overrides.push_back(o);
  testing::CaseRun coarse("liakopoulos.yaml", coarse_overrides);
  ASSERT_GT(run.initialisation_steps, 0u);
  ASSERT_DOUBLE_EQ(run.engine->time(), 0.0);  // the clock restarts after the initialisation
  Layers at300;
  testing::WallWatch walls(run.spec);  // issue 13, item 1
  walls.sample(run.engine->frame());
  for (int k = 0; k < 3; ++k) {
    const double t = Reference::times[k];
    run.run_until(t / kAlpha);
    walls.sample(run.engine->frame());
    const Layers now = layers(run.engine->frame());
    if (k == 0) at300 = now;
    const double* pressure = Reference::pressure(k);
    const double scale = std::fabs(pressure[Reference::points - 1]);  // |p_w| at the top
    double worst = 0;
    for (std::size_t l = 0; l < now.z.size(); ++l)
      worst = testing::worst_of(worst, std::fabs(now.pressure[l] - Reference::interpolate(pressure, now.z[l])));
    char metric[160];
    std::snprintf(metric, sizeof metric, "largest layer |p_w − p_OGS| / |p_OGS| at the top, t = %.0f s", t);
    CASCADE_VALIDATE({.case_name = case_name, .reference = ogs, .metric = metric, .measured = worst / scale,
                      .reference_value = 0.10, .bound = testing::Bound::at_most,
                      .tolerance_source = "the differences from OGS listed in the file (K_w, Eq. 43a's γ_w, 20 "
                                          "particles) and the spread of published solutions (Schrefler & Scotta "
                                          "2001, Lewis & Schrefler 1998, OGS, the paper's SPH): some 10% of the top "
                                          "suction in the first 10 minutes"});
    std::snprintf(metric, sizeof metric, "top layer's settlement u_z (z = %.3f m), t = %.0f s (m)", now.z.back(), t);
    CASCADE_VALIDATE({.case_name = case_name, .reference = ogs, .metric = metric, .measured = now.settlement.back(),
                      .reference_value = Reference::interpolate(Reference::displacement(k), now.z.back()),
                      .tolerance = 0.20, .relative = true,
                      .tolerance_source = "the pressure's differences (K_w, Eq. 43a's γ_w, 20 particles) plus some 8% "
                                          "at 300 s from the initialisation's excess pore pressure consolidating; "
                                          "20% itself not derived"});
    // The settlement's ratio to OGS at each resolution's own top layer, extrapolated to dp → 0
    // with first-order convergence (assumed: two resolutions cannot give the order).
    coarse.run_until(t / kAlpha);
    const Layers coarse_now = layers(coarse.engine->frame());
    const double fine_ratio = now.settlement.back() / Reference::interpolate(Reference::displacement(k), now.z.back());
    const double coarse_ratio =
        coarse_now.settlement.back() / Reference::interpolate(Reference::displacement(k), coarse_now.z.back());
    std::snprintf(metric, sizeof metric,
                  "top layer's settlement / OGS's, dp 0.1 and 0.05 m extrapolated to dp → 0, t = %.0f s", t);
    CASCADE_VALIDATE({.case_name = case_name, .reference = ogs, .metric = metric,
                      .measured = 2 * fine_ratio - coarse_ratio, .reference_value = 1.0, .tolerance = 0.20,
                      .tolerance_source = "as the settlement at dp 0.05 m: the pressure's differences (K_w, Eq. 43a's "
                                          "γ_w) plus some 8% at 300 s from the initialisation; 20% itself not derived"});
  }

  walls.validate(case_name, "at the start and the three reference times");

  // The scaling in time holds: half the acceleration gives the same profile at 300 s.
  constexpr double kCheckAlpha = 50.0;
  testing::CaseRun check("liakopoulos.yaml", testing::accelerated_liakopoulos(kCheckAlpha));
  check.run_until(Reference::times[0] / kCheckAlpha);
  const Layers other = layers(check.engine->frame());
  ASSERT_EQ(other.z.size(), at300.z.size());
  double largest = 0;
  for (std::size_t l = 0; l < other.z.size(); ++l)
    largest = testing::worst_of(largest, std::fabs(other.pressure[l] - at300.pressure[l]));
  const double scale = std::fabs(Reference::pressure(0)[Reference::points - 1]);
  CASCADE_VALIDATE({.case_name = case_name,
                    .reference = "the same case at α = 50: quasi-static, the solution depends on K t only",
                    .metric = "largest layer |p_w(α = 50) − p_w(α = 100)| / |p_OGS| at the top, t = 300 s",
                    .measured = largest / scale, .reference_value = 0.01, .bound = testing::Bound::at_most,
                    .tolerance_source = "1% of the top pressure, not derived in the test (no independent source "
                                        "yet)"});
}

}  // namespace
}  // namespace cascade
