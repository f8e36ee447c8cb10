// cascade-server launched by mpirun (issue 17): process 0 serves gRPC and runs every session as
// one process does; each session's engine is split over all the processes. Process 0's engine
// (LeaderEngine) hands every call that changes the run or needs the others (a step, a forcing
// change, a frame, a checkpoint's state, a restore) to them before it makes it itself, so that
// every command reaches all processes at the same step boundary, in the order the session's
// solver thread applies them; the others (follow_split_engines) make the same calls on their
// shares. Each engine has a communicator of its own, so that sessions run side by side.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "cascade/v1/scenario.pb.h"
#include "server/core/engine.h"

namespace cascade {

using SplitEngineFactory = std::function<std::unique_ptr<Engine>(const EngineConfig&, const HostParticles&)>;

// On process 0. MPI must be initialised with MPI_THREAD_MULTIPLE (MpiSession).
class SplitEngineLauncher {
 public:
  // The factory of a session's engines: each is split over all processes, which build their
  // shares from `spec` (defaults applied). The stages above it (server/solver) run on process 0
  // alone and reach the others through the engine's calls (a stage hand-over is a restore).
  SplitEngineFactory factory(const v1::ScenarioSpec& spec);
  // Ends follow_split_engines on the other processes: after every engine is destroyed.
  void finish();

  // A new engine of the case (`case_bytes`, its ScenarioSpec serialised), split over all
  // processes: announced to the others, with a communicator of its own. A fork's engine is one
  // such, restored from its parent's state.
  std::unique_ptr<Engine> launch(const std::string& case_bytes, const EngineConfig& config,
                                 std::shared_ptr<const HostParticles> whole);

 private:
  std::mutex world_;  // the announcements and the communicators they make: one order on every process
};

// On the other processes: builds the share of every engine process 0 announces and follows its
// calls on a thread of its own, until SplitEngineLauncher::finish. `precision`, `device` and
// `threads` as process 0's (the same command line).
void follow_split_engines(Precision precision, Device device, int threads);

}  // namespace cascade
