// The 3D landslide-tsunami flume (cases/landslide_tsunami_3d.yaml, Section 4.4 after Viroulet et
// al. 2013, extruded over a periodic strip): it loads, builds its particles and runs. The wave
// itself is validated in 2D (test_landslide_tsunami_2d.cpp, docs/cases.md "Landslide tsunami").
#include <gtest/gtest.h>

#include <cmath>

#include "tests/validation/case_run.h"

namespace cascade {
namespace {

struct PhaseCounts {
  std::size_t water = 0, soil = 0, outside = 0;
};

PhaseCounts count(const FieldFrame& f, const v1::ScenarioSpec& spec) {
  PhaseCounts n;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double x = f.position[3 * i], z = f.position[3 * i + 2];
    const int vertical = spec.dimensions() - 1;  // the domain's z index
    const bool inside = x >= spec.domain().min(0) && x <= spec.domain().max(0) &&
                        z >= spec.domain().min(vertical) && z <= spec.domain().max(vertical) && std::isfinite(x) &&
                        std::isfinite(z);
    if (f.phase[i] == std::uint8_t(Phase::water)) ++n.water;
    if (f.phase[i] == std::uint8_t(Phase::soil)) ++n.soil;
    if (f.phase[i] != std::uint8_t(Phase::boundary) && !inside) ++n.outside;
  }
  return n;
}

// The soil's centroid height and the speed of its centroid (all particles have one mass).
void soil_centroid(const FieldFrame& f, double* z, double* speed) {
  const auto* v = f.find("velocity");
  double zc = 0, vx = 0, vz = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.phase[i] != std::uint8_t(Phase::soil)) continue;
    zc += f.position[3 * i + 2], vx += v->values[3 * i], vz += v->values[3 * i + 2], ++n;
  }
  *z = zc / double(n);
  *speed = std::hypot(vx, vz) / double(n);
}

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
  EXPECT_EQ(n1.water, n0.water);
  EXPECT_EQ(n1.soil, n0.soil);
  EXPECT_EQ(n1.outside, 0u);
  EXPECT_GT(speed, 0.0);
  EXPECT_TRUE(std::isfinite(speed));
}

}  // namespace
}  // namespace cascade
