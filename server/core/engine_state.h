// Everything an Engine carries from one step to the next (Engine::state, Engine::restore): a
// checkpoint's content. Arrays are in the engine's own particle order (sorted by cell at its last
// neighbour-list build, with the particle ids among them), so that an engine restored from it
// lists the same neighbours in the same order and its next steps give the same bits as the steps
// of the engine it was taken from.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "server/core/hydraulic_forcing.h"

namespace cascade {

struct EngineState {
  int dimensions = 0;
  bool single_precision = false;  // the engine's Real: float values are exact in the doubles below
  std::size_t particles = 0;
  double time = 0;
  double last_dt = 0;
  std::uint64_t steps = 0;
  HydraulicForcing forcing;
  // Per-particle arrays by name, their components flattened (particles × components).
  std::map<std::string, std::vector<double>> reals;
  std::map<std::string, std::vector<std::uint32_t>> integers;
  // The positions that displacements are measured from, by id (particles × 3).
  std::vector<double> displacement_reference;
  // The stage running (Engine::stage) and named numbers that a stage carries over a checkpoint.
  int stage = 0;
  std::map<std::string, double> stage_values;
};

}  // namespace cascade
