// Walls that hold (issue 13, item 1): no water or soil particle centre gets deeper than dp/2 into
// a solid (tests/validation/solid_depth.h), at the two smoothing lengths the cases use, h/dp = 1.3
// and 1.5, in the two situations that let particles through before the impenetrable-wall
// condition (docs/physics.md, "Impenetrable walls"):
//  - a dry soil block thrown at 10 m/s against a vertical wall (cases/wall_impact_2d.yaml), to
//    0.2 s, sampled every millisecond through the impact;
//  - a moist soil block at rest on the floor against the wall, with 50 kPa suction in Gardner's
//    curve at α = 0.5 /m (S_w = 0.08: Bishop's stress, Eq. 7, carries about 4 kPa of suction), to
//    0.5 s.
// Each also keeps every particle in the domain.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "tests/validation/case_run.h"
#include "tests/validation/slide_counts.h"
#include "tests/validation/solid_depth.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

void run_against_the_wall(const std::string& case_name, const std::vector<std::string>& overrides, double end,
                          double sample) {
  testing::CaseRun run("wall_impact_2d.yaml", overrides);
  const testing::SolidDepth solids(run.spec);
  const double half_spacing = 0.5 * run.config.dp;
  const FieldFrame start = run.engine->frame();
  const testing::PhaseCounts n0 = testing::count(start, run.spec);
  testing::SolidDepth::Count worst = solids.inside(start, half_spacing);
  for (double t = sample; t <= end + 1e-9; t += sample) {
    run.run_until(t);
    worst.keep_worst(solids.inside(run.engine->frame(), half_spacing));
  }
  std::printf("%s: deepest %.3g mm inside a wall, at most %zu particles deeper than dp/2\n", case_name.c_str(),
              1e3 * worst.deepest, worst.deeper);
  testing::validate_nothing_lost(case_name, n0, testing::count(run.engine->frame(), run.spec), "at the end");
  testing::validate_outside_solids(case_name, worst, half_spacing, "at any sample");
}

TEST(Walls, FastSlideStaysOutside) {
  for (const char* h_over_dp : {"1.3", "1.5"})
    run_against_the_wall(std::string("Soil block at 10 m/s against a wall, h/dp = ") + h_over_dp +
                             " (cases/wall_impact_2d.yaml)",
                         {std::string("h_over_dp=") + h_over_dp}, 0.2, 1e-3);
}

TEST(Walls, MoistSoilRestingOnTheWallStaysOutside) {
  for (const char* h_over_dp : {"1.3", "1.5"})
    run_against_the_wall(std::string("Moist soil block at rest against a wall, 50 kPa suction, h/dp = ") + h_over_dp +
                             " (cases/wall_impact_2d.yaml)",
                         {std::string("h_over_dp=") + h_over_dp, "bodies[4].initial.velocity=[0,0]",
                          "bodies[4].initial.suction=5e4", "materials[0].soil.hydraulic.gardner.alpha=0.5",
                          "bodies[4].shape.box.min=[0.7,0.0]", "bodies[4].shape.box.max=[1.0,0.1]"},
                         0.5, 5e-3);
}

}  // namespace
}  // namespace cascade
