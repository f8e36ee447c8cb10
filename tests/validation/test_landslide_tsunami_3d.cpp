// The 3D landslide-tsunami flume (cases/landslide_tsunami_3d.yaml, Section 4.4 after Viroulet et
// al. 2013, extruded over a periodic strip): it loads, builds its particles and runs. The wave
// itself is validated in 2D (test_landslide_tsunami_2d.cpp, docs/cases.md "Landslide tsunami").
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/validation/case_run.h"
#include "tests/validation/slide_counts.h"

namespace cascade {
namespace {

using testing::count;
using testing::PhaseCounts;
using testing::soil_centroid;

// The 3D flume (cases/landslide_tsunami_3d.yaml) loads, builds its particles and runs: the slide
// starts moving and nothing is lost in 20 steps.
TEST(LandslideTsunami3d, LoadsAndRunsAFewSteps) {
  testing::CaseRun run("landslide_tsunami_3d.yaml");
  const PhaseCounts n0 = count(run.engine->frame(), run.spec);
  run.run_steps(20);
  const FieldFrame f = run.engine->frame();
  const PhaseCounts n1 = count(f, run.spec);
  double z = 0, speed = 0;
  soil_centroid(f, &z, &speed);
  EXPECT_GT(n0.water, 10000u);
  EXPECT_GT(n0.soil, 300u);
  const std::string case_name = "Landslide into a flume 3D (cases/landslide_tsunami_3d.yaml)";
  testing::validate_nothing_lost(case_name, n0, n1, "after 20 steps");
  EXPECT_GT(speed, 0.0);
  EXPECT_TRUE(std::isfinite(speed));
}

}  // namespace
}  // namespace cascade
