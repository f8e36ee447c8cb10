// Checkpoints of a run split over processes (issue 17): a state taken at N processes restores at
// any M and goes on as the run that was never stopped. Launched by ctest through mpirun at 1 to 4
// processes (tests/CMakeLists.txt); at N processes, for every M from N down to 1:
//  - the split run steps to step s1, its state (DistributedEngine::state, the whole run's) goes
//    through a checkpoint file (write_checkpoint, read back by every process), and a split run
//    over the first M processes restores it and steps to s2;
//  - at M = 1 also one process's engine (Simulation::restore) restores it;
//  - the other way, one process's state at s1 restores at N processes.
// Each restored run's frame at s2 is compared with one process's run that never stopped, on the
// 2D dam break (water) and the submerged soil layer (soil and pore water): positions within 1e-9
// dp and every field within 1e-7 of its range, the round-off of sums taken in another order as in
// test_split_run.cpp (the restored shares list their neighbours anew, at the positions of s1);
// the same step at the same time; every particle there once (DistributedEngine::frame); the
// pore-water account (the volumes that entered since the start) within 1e-9 of its size.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "server/io/checkpoint_file.h"
#include "server/parallel/distributed_engine.h"
#include "server/parallel/mpi_transport.h"
#include "tests/parallel/frame_difference.h"
#include "tests/parallel/mpi_test_main.h"
#include "tests/validation/case_run.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

MpiTransport* world = nullptr;

// The same bytes on every process: process 0's.
std::vector<char> from_process_0(const std::vector<char>& message) {
  return world->exchange(std::vector<std::vector<char>>(world->processes(), message))[0];
}

void step_to(Engine& engine, std::uint64_t step) {
  while (engine.step_count() < step) engine.step();
}

// A state through a checkpoint file, written by process 0 and read by every process.
EngineState through_file(const EngineState& state, const std::string& name) {
  const std::filesystem::path path =
      std::filesystem::path(CASCADE_BINARY_DIR) / ("split_checkpoint_" + name + "_" + std::to_string(world->processes()) + ".h5");
  if (world->process() == 0) {
    Checkpoint c;
    c.simulation = "simulations/" + name;
    c.engine = state;
    write_checkpoint(path, c);
  }
  from_process_0({});  // written before anyone reads it
  EngineState read = read_checkpoint(path).engine;
  from_process_0({});
  if (world->process() == 0) std::filesystem::remove(path);
  return read;
}

void checkpoint_restores_at_any_count(const std::string& case_file, const std::string& case_name, double t1, double t2,
                                      const std::vector<std::string>& overrides = {}) {
  const int processes = world->processes(), me = world->process();
  testing::CaseRun alone(case_file, overrides);
  // One process's run, never stopped: its steps at t1 and t2, its state at t1, its frame at t2.
  std::uint64_t steps[2] = {0, 0};
  EngineState alone_state;
  FieldFrame reference;
  PoreWaterAccount reference_account;
  if (me == 0) {
    alone.run_until(t1);
    steps[0] = alone.engine->step_count();
    alone_state = alone.engine->state();
    alone.run_until(t2);
    steps[1] = alone.engine->step_count();
    reference = alone.engine->frame();
    reference_account = alone.engine->pore_water_account();
  }
  {
    std::vector<char> bytes(sizeof steps);
    std::memcpy(bytes.data(), steps, sizeof steps);
    const std::vector<char> shared = from_process_0(bytes);
    std::memcpy(steps, shared.data(), sizeof steps);
  }
  ASSERT_GT(steps[1], steps[0]);
  const double dp = alone.config.dp;
  testing::FrameDifference worst;
  auto compare = [&](const Engine& restored, const std::string& how) {
    const FieldFrame f = restored.frame();
    const PoreWaterAccount account = restored.pore_water_account();
    if (me != 0) return;
    // The pore water that entered since the start, carried over the checkpoint (process 0 carries
    // it on in a split run): the same volumes to round-off.
    const double scale = std::abs(reference_account.rain) + std::abs(reference_account.walls) +
                         std::abs(reference_account.surface);
    EXPECT_LE(std::abs(account.rain - reference_account.rain) + std::abs(account.walls - reference_account.walls) +
                  std::abs(account.surface - reference_account.surface),
              1e-9 * scale)
        << how;
    EXPECT_EQ(restored.step_count(), steps[1]);
    EXPECT_NEAR(f.time, reference.time, 1e-12 * reference.time) << how;
    const testing::FrameDifference d = testing::frame_difference(f, reference, dp);
    std::printf("%s: %s: largest |Δx| %.3g dp, |Δ field| %.3g of its range (%s); rain in %.6g (%.6g never stopped)\n",
                case_file.c_str(), how.c_str(), d.position, d.field, d.worst_field.c_str(), account.rain,
                reference_account.rain);
    worst.widen(d);
  };

  // Taken at N processes, through a file.
  DistributedEngine split(alone.config, alone.set.particles, *world);
  step_to(split, steps[0]);
  const EngineState taken = through_file(split.state(), "split");
  EXPECT_EQ(taken.steps, steps[0]);
  for (int m = processes; m >= 1; --m) {
    MPI_Comm part = MPI_COMM_NULL;
    MPI_Comm_split(MPI_COMM_WORLD, me < m ? 0 : MPI_UNDEFINED, me, &part);
    if (part != MPI_COMM_NULL) {
      MpiTransport transport(part);
      DistributedEngine restored(alone.config, alone.set.particles, transport);
      restored.restore(taken);
      step_to(restored, steps[1]);
      compare(restored, "taken at " + std::to_string(processes) + ", restored at " + std::to_string(m) + " processes");
      MPI_Comm_free(&part);
    }
  }
  if (me == 0) {  // by one process's engine
    testing::CaseRun one(case_file, overrides);
    one.engine->restore(taken);
    step_to(*one.engine, steps[1]);
    compare(*one.engine, "taken at " + std::to_string(processes) + " processes, restored by one process's engine");
  }
  // Taken by one process's engine, restored at N processes.
  {
    const EngineState from_one = through_file(alone_state, "one");
    DistributedEngine restored(alone.config, alone.set.particles, *world);
    restored.restore(from_one);
    step_to(restored, steps[1]);
    compare(restored, "taken by one process's engine, restored at " + std::to_string(processes) + " processes");
  }
  if (me != 0) return;
  const std::string detail = ", " + std::to_string(processes) + " processes, restored at every count to 1 and by one "
                             "process's engine, and one process's state restored at " + std::to_string(processes) +
                             "; worst at t = " + testing::validation_detail::json_number(t2) + " s after a checkpoint at " +
                             testing::validation_detail::json_number(t1) + " s";
  const std::string reference_run = "the same run in one process, never stopped";
  const std::string source = "round-off: the restored shares sum a particle's neighbours in another order (test_split_run.cpp)";
  CASCADE_VALIDATE({.case_name = case_name, .reference = reference_run,
                    .metric = "largest |x − x_never stopped| / dp" + detail, .measured = worst.position,
                    .reference_value = 1e-9, .bound = testing::Bound::at_most, .tolerance_source = source});
  CASCADE_VALIDATE({.case_name = case_name, .reference = reference_run,
                    .metric = "largest |field − field_never stopped| / the field's range, every field (worst: " +
                              worst.worst_field + ")" + detail,
                    .measured = worst.field, .reference_value = 1e-7, .bound = testing::Bound::at_most,
                    .tolerance_source = source});
}

TEST(SplitCheckpoint, DamBreak2DRestoresAtAnyProcessCount) {
  checkpoint_restores_at_any_count("dam_break_2d.yaml", "2D dam break (cases/dam_break_2d.yaml, dp = a/20)", 0.03, 0.06,
                                   {"dp=0.0073"});
}
TEST(SplitCheckpoint, SubmergedLayerRestoresAtAnyProcessCount) {
  checkpoint_restores_at_any_count("submerged_layer_2d.yaml", "Submerged soil layer (cases/submerged_layer_2d.yaml)",
                                   0.01, 0.02);
}

// Rain into the unsaturated column: the pore-water account's rain carried over the checkpoint.
TEST(SplitCheckpoint, InfiltrationColumnRestoresAtAnyProcessCount) {
  checkpoint_restores_at_any_count("infiltration_1d.yaml", "Infiltration column (cases/infiltration_1d.yaml)", 900.0, 1800.0);
}

}  // namespace
}  // namespace cascade

int main(int argc, char** argv) { return cascade::testing::mpi_test_main(argc, argv, cascade::world); }
