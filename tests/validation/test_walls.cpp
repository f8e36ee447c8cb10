// Walls that hold (issue 13, item 1): no water or soil particle centre gets deeper than dp/2 into
// a solid (tests/validation/solid_depth.h), at the two smoothing lengths the cases use, h/dp = 1.3
// and 1.5, in the two situations that let particles through before the impenetrable-wall
// condition (docs/physics.md, "Impenetrable walls"):
//  - a dry soil block thrown at 10 m/s against a vertical wall (cases/wall_impact_2d.yaml), to
//    0.2 s, sampled every millisecond through the impact;
//  - a moist soil block at rest on the floor against the wall, with 50 kPa suction in Gardner's
//    curve at α = 0.5 /m (S_w = 0.08: Bishop's stress, Eq. 7, carries about 4 kPa of suction), to
//    0.5 s.
// Each also keeps every particle in the domain. The README's storm demo, through its slide, is the
// third (below); the other cases of the suite count the same figure in their own tests.
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
  testing::WallWatch walls(run.spec);
  const FieldFrame start = run.engine->frame();
  const testing::PhaseCounts n0 = testing::count(start, run.spec);
  walls.sample(start);
  for (double t = sample; t <= end + 1e-9; t += sample) {
    run.run_until(t);
    walls.sample(run.engine->frame());
  }
  testing::validate_nothing_lost(case_name, n0, testing::count(run.engine->frame(), run.spec), "at the end");
  walls.validate(case_name, "at any sample");
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

// The README's main job (cases/cascade_storm_2d.yaml, the demo's case without the operator's
// raise): its storm to the failure, then 15 s of the slide stage, which take the slide into the
// channel and the wave over the far bank (overtopping about 3 s after the failure). Sampled at
// every step of the rain stage and every 0.05 s of the slide.
TEST(Walls, StormDemoStaysOutsideThroughTheSlide) {
  testing::CaseRun run("cascade_storm_2d.yaml");
  testing::WallWatch walls(run.spec);
  const FieldFrame start = run.engine->frame();
  const testing::PhaseCounts n0 = testing::count(start, run.spec);
  walls.sample(start);
  while (run.engine->stage() < 2 && run.engine->time() < run.spec.end_time()) {
    run.step();
    walls.sample(run.engine->frame());
  }
  ASSERT_EQ(run.engine->stage(), 2) << "the slope did not fail by the case's end time";
  const double failure = run.engine->time();
  for (int k = 1; k <= 300; ++k) {
    run.run_until(failure + 0.05 * k);
    walls.sample(run.engine->frame());
  }
  const std::string case_name = "Storm cascade demo, through 15 s of the slide (cases/cascade_storm_2d.yaml)";
  testing::validate_nothing_lost(case_name, n0, testing::count(run.engine->frame(), run.spec), "at the end");
  walls.validate(case_name, "at any sample");
}

}  // namespace
}  // namespace cascade
