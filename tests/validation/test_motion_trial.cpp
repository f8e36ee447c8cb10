// The rain stage's motion trials (StageEnd.motion, server/solver/staged_engine.cpp) leave nothing
// behind: a trial runs the dynamic engine from the stage's state and puts that state back. The
// storm case (cases/cascade_storm_2d.yaml) run to 3 h of rain twice, once ending its rain stage by
// motion (trials every 10 min once soil is at yield; the slope stands until about 4.3 h, so none
// moves it) and once by time alone, must give the same bits; and a run restored from a state
// taken between trials must take the same trials and give the same bits again.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/validation/case_run.h"

namespace cascade {
namespace {

constexpr double kUntil = 3 * 3600.0;  // s of rain: soil at yield, the slope still standing

void run_until(Engine& engine, double time) {
  while (engine.time() < time) engine.step();
}

void expect_same_bits(const FieldFrame& a, const FieldFrame& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.position, b.position);
  for (const char* field : {"velocity", "pore_pressure", "saturation", "effective_stress", "yield_ratio"})
    EXPECT_EQ(a.find(field)->values, b.find(field)->values) << field;
}

std::string reasons(Engine& engine) {
  std::string all;
  for (const StageChange& c : engine.take_stage_changes()) all += c.reason + "\n";
  return all;
}

TEST(MotionTrial, TrialsLeaveTheStateAsTheyFoundIt) {
  testing::CaseRun trials("cascade_storm_2d.yaml");
  testing::CaseRun plain("cascade_storm_2d.yaml", {"stages[1].end={time: 1 day}"});
  run_until(*trials.engine, kUntil);
  run_until(*plain.engine, kUntil);
  ASSERT_EQ(trials.engine->stage(), 1) << "the slope must still stand at 3 h: " << reasons(*trials.engine);
  const EngineState state = trials.engine->state();
  ASSERT_TRUE(state.stage_values.count("motion.trials")) << "no trial ran: no soil at yield by 3 h";
  std::printf("motion trials by %.0f s of rain: %.0f, the last at %.0f s\n", kUntil, state.stage_values.at("motion.trials"),
              state.stage_values.at("motion.last_trial_time"));
  expect_same_bits(trials.engine->frame(), plain.engine->frame());
}

TEST(MotionTrial, RestoredBetweenTrialsTakesTheSameTrials) {
  testing::CaseRun first("cascade_storm_2d.yaml");
  run_until(*first.engine, 2 * 3600.0);
  const EngineState taken = first.engine->state();
  run_until(*first.engine, kUntil);
  testing::CaseRun second("cascade_storm_2d.yaml");
  second.engine->restore(taken);
  run_until(*second.engine, kUntil);
  expect_same_bits(first.engine->frame(), second.engine->frame());
  EXPECT_EQ(first.engine->state().stage_values, second.engine->state().stage_values);
}

}  // namespace
}  // namespace cascade
