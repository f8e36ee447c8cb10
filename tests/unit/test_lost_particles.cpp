// A particle that leaves the domain is counted (Engine::lost_particles) and flagged in every frame
// (the `lost` field), with its phase kept: a count of a phase cannot hide it (issue 14). The test
// kicks one water particle of the dam break out through the open top on purpose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"

namespace cascade {
namespace {

std::size_t flagged(const FieldFrame& f) {
  const auto* lost = f.find("lost");
  EXPECT_NE(lost, nullptr);
  if (!lost) return 0;
  return std::size_t(std::count(lost->values.begin(), lost->values.end(), 1.0));
}

TEST(LostParticles, AParticleKickedOutOfTheDomainIsCountedAndFlagged) {
  const auto spec =
      load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/dam_break_2d.yaml", {{"dp", "0.02"}});
  HostParticles particles = build_particle_set(spec).particles;
  const EngineConfig config = engine_config(spec, particles, Precision::double_precision);
  // The highest water particle, sent up at 30 m/s: the tank is open above and the domain ends at
  // z = 0.8 m, 0.5 m over it.
  std::size_t kicked = particles.phase.size();
  for (std::size_t i = 0; i < particles.phase.size(); ++i)
    if (particles.phase[i] == Phase::water &&
        (kicked == particles.phase.size() || particles.position[2 * i + 1] > particles.position[2 * kicked + 1]))
      kicked = i;
  ASSERT_LT(kicked, particles.phase.size());
  particles.velocity[2 * kicked + 1] = 30.0;
  const auto engine = make_engine(config, particles);

  const FieldFrame start = engine->frame();
  EXPECT_EQ(flagged(start), 0u);
  EXPECT_EQ(engine->lost_particles(), 0u);
  int steps = 0;
  while (engine->lost_particles() == 0 && steps < 5000) engine->step(), ++steps;
  ASSERT_EQ(engine->lost_particles(), 1u) << "after " << steps << " steps";
  const FieldFrame f = engine->frame();
  EXPECT_EQ(flagged(f), 1u);
  const auto* lost = f.find("lost");
  ASSERT_NE(lost, nullptr);
  EXPECT_EQ(lost->values[kicked], 1.0) << "the flag is on another particle";
  EXPECT_EQ(f.phase[kicked], std::uint8_t(Phase::water)) << "a lost particle keeps its phase";
  EXPECT_GT(f.position[3 * kicked + 2], 0.8) << "it left through the top";
}

}  // namespace
}  // namespace cascade
