// Still water in an open tank (cases/hydrostatic_tank_2d.yaml, _3d.yaml): after 10⁴ steps the
// pressure is hydrostatic, ρ g (H − z), within 2% below the top three particle layers (averaged
// over each layer, the way a pressure profile is read), and no water particle has crossed a wall.
// The reference is the analytic hydrostatic solution; 2% is the accuracy weakly compressible SPH
// reaches for it with dummy-particle walls (e.g. English et al. 2022, mDBC, Comp. Part. Mech. 9).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "tests/validation/case_run.h"
#include "tests/validation/solid_depth.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

void check_hydrostatic(const std::string& case_file, const std::vector<std::string>& overrides,
                       const std::array<double, 3>& tank_max) {
  testing::CaseRun run(case_file, overrides);
  const double dp = run.spec.dp();
  const double rho0 = run.config.water_density;
  const double g = std::fabs(run.config.gravity[run.config.dimensions - 1]);
  const std::size_t water = run.set.particles.count(Phase::water);

  testing::WallWatch walls(run.spec);  // issue 13, item 1: every 1000 steps
  walls.sample(run.engine->frame());
  for (int k = 0; k < 10; ++k) {
    run.run_steps(1000);
    walls.sample(run.engine->frame());
  }
  ASSERT_EQ(run.engine->lost_particles(), 0u);
  const FieldFrame frame = run.engine->frame();
  const auto p = testing::water_values(frame, "pressure");
  ASSERT_EQ(p.z.size(), water);

  // No water particle outside the tank's interior (walls at 0 and tank_max along x, y; floor z = 0).
  for (std::size_t i = 0; i < p.z.size(); ++i) {
    EXPECT_GT(p.x[i], 0.0) << "particle through the left wall";
    EXPECT_LT(p.x[i], tank_max[0]) << "particle through the right wall";
    if (run.config.dimensions == 3) {
      EXPECT_GT(p.y[i], 0.0);
      EXPECT_LT(p.y[i], tank_max[1]);
    }
    EXPECT_GT(p.z[i], 0.0) << "particle through the floor";
  }

  // Free surface H: the top layer's particle centres plus dp/2.
  const double top = *std::max_element(p.z.begin(), p.z.end());
  const double surface = top + 0.5 * dp;
  // Layer averages: particles binned by their lattice layer.
  std::map<int, std::pair<double, double>> layers;  // layer → (Σ p, Σ z) ...
  std::map<int, int> counts;
  for (std::size_t i = 0; i < p.z.size(); ++i) {
    const int layer = int(std::floor(p.z[i] / dp));
    layers[layer].first += p.value[i];
    layers[layer].second += p.z[i];
    ++counts[layer];
  }
  int checked = 0;
  double worst = 0;  // a NaN layer counts as infinite: it fails the figure
  for (const auto& [layer, sums] : layers) {
    const double z = sums.second / counts[layer];
    // The top three layers, whose centres lie near 0.5, 1.5 and 2.5 dp below the surface: the cut
    // lies half-way to the fourth (3.5 dp), not on it, where a layer's mean z a fraction of a
    // millimetre high dropped it from the check (0.3 mm in the 3D tank, docs/physics.md,
    // "Verification").
    if (z > surface - 3.0 * dp) continue;
    const double expected = rho0 * g * (surface - z);
    const double error = std::fabs(sums.first / counts[layer] - expected) / expected;
    worst = std::max(worst, std::isnan(error) ? INFINITY : error);
    ++checked;
  }
  EXPECT_GE(checked, int(std::lround(surface / dp)) - 3);  // every layer below the top three
  char metric[160];
  std::snprintf(metric, sizeof metric,
                "largest |layer-mean p − ρ g (H − z)| / ρ g (H − z) below the top three layers, 10⁴ steps, dp = %g m",
                dp);
  const std::string case_name =
      "Hydrostatic tank " + std::to_string(run.config.dimensions) + "D (cases/" + case_file + ")";
  walls.validate(case_name, "at any of the 11 samples");
  CASCADE_VALIDATE({.case_name = case_name,
                    .reference = "analytic hydrostatic pressure ρ g (H − z), H the measured free surface",
                    .metric = metric, .measured = worst, .reference_value = 0.02, .bound = testing::Bound::at_most,
                    .tolerance_source = "the accuracy weakly compressible SPH reaches with dummy-particle walls (e.g. "
                                        "English et al. 2022, mDBC, Comp. Part. Mech. 9)"});
}

TEST(HydrostaticTank, TwoDimensional) { check_hydrostatic("hydrostatic_tank_2d.yaml", {}, {1.0, 0, 0}); }

// dp = 0.025 keeps the 3D run within a CI budget (12 layers of water).
TEST(HydrostaticTank, ThreeDimensional) {
  check_hydrostatic("hydrostatic_tank_3d.yaml", {"dp=0.025"}, {0.5, 0.3, 0});
}

}  // namespace
}  // namespace cascade
