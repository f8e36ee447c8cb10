// The 3D rainfall-landslide-tsunami case (cases/cascade_3d.yaml, Section 5, Table 3): at its dp of
// 0.1 m it builds about the paper's 1,436,550 particles, and, coarsened, it loads and runs its
// first steps of rain with every particle kept. Its full run (of the order of 10⁶ steps) is for a
// GPU; bench/bench_cascade.cpp measures a 10⁶-particle slice on the CPU (docs/performance.md).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "server/scenario/case_loader.h"
#include "server/scenario/particle_builder.h"
#include "tests/validation/case_run.h"

namespace cascade {
namespace {

TEST(Cascade3d, BuildsAboutThePapersParticleCountAtItsResolution) {
  const auto spec = load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/cascade_3d.yaml", {});
  const auto particles = build_particles(spec);
  const double paper = 1436550;
  std::printf("cascade_3d at dp = 0.1 m: %zu particles (%zu water, %zu soil, %zu boundary); the paper's %.0f\n",
              particles.size(), particles.count(Phase::water), particles.count(Phase::soil),
              particles.count(Phase::boundary), paper);
  EXPECT_NEAR(double(particles.size()) / paper, 1.0, 0.05);
  EXPECT_GT(particles.count(Phase::soil), 200000u);
  EXPECT_GT(particles.count(Phase::water), 400000u);
}

// At dp = 0.4 m (about 2·10⁴ particles): the rain enters the slope's surface, the pore pressure
// there rises, nothing is lost and every value stays finite over 100 steps.
TEST(Cascade3d, CoarseRunStartsRainingWithEveryParticleKept) {
  testing::CaseRun run("cascade_3d.yaml", {"dp=0.4"});
  const FieldFrame f0 = run.engine->frame();
  run.run_steps(100);
  const FieldFrame f1 = run.engine->frame();
  ASSERT_EQ(f1.size(), f0.size());
  EXPECT_EQ(run.engine->lost_particles(), 0u);
  const auto* p0 = f0.find("pore_pressure");
  const auto* p1 = f1.find("pore_pressure");
  ASSERT_TRUE(p0 && p1);
  double rise_surface = 0;
  std::size_t n_surface = 0;
  for (std::size_t i = 0; i < f1.size(); ++i) {
    if (f1.phase[i] != std::uint8_t(Phase::soil)) continue;
    ASSERT_TRUE(std::isfinite(p1->values[i])) << "particle " << f1.id[i];
    if (f1.free_surface[i]) rise_surface += p1->values[i] - p0->values[i], ++n_surface;
  }
  ASSERT_GT(n_surface, 0u);
  std::printf("after %.3f s of rain: mean pore-pressure rise at %zu surface particles %.1f Pa\n", run.engine->time(),
              n_surface, rise_surface / double(n_surface));
  EXPECT_GT(rise_surface / double(n_surface), 0.0);
}

}  // namespace
}  // namespace cascade
