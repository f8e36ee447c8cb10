// A checkpoint: one simulation's complete state at a step boundary in one HDF5 file, enough to go
// on bit-identically on the CPU (the engine's state, engine_state.h), to rebuild the engine (the
// case's ScenarioSpec) and to keep the record of the run (its journal so far). Layout in
// docs/api.md ("Checkpoints"). The HDF5 headers stay in the .cpp file.
#pragma once

#include <filesystem>
#include <string>

#include "cascade/v1/scenario.pb.h"
#include "server/core/engine_state.h"

namespace cascade {

struct Checkpoint {
  std::string simulation;  // simulations/{id}
  double wall_time = 0;    // Unix seconds when taken
  v1::ScenarioSpec spec;   // defaults applied
  std::string journal;     // journal.jsonl up to and with the checkpoint's own entry
  EngineState engine;
};

// What a listing shows without reading the arrays.
struct CheckpointSummary {
  std::string simulation;
  std::string case_name;
  double wall_time = 0;
  double time = 0;
  std::uint64_t step = 0;
  std::size_t particles = 0;
};

// Writes `path` through a temporary file beside it, renamed when complete, so that a crash leaves
// either the whole checkpoint or none. Throws std::runtime_error.
void write_checkpoint(const std::filesystem::path& path, const Checkpoint& checkpoint);
// Throws std::runtime_error naming the file and what is wrong with it.
Checkpoint read_checkpoint(const std::filesystem::path& path);
CheckpointSummary read_checkpoint_summary(const std::filesystem::path& path);

}  // namespace cascade
