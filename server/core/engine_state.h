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

// The pore water that entered the soil since the run began, by where it crossed (m³, per metre of
// depth in 2D; negative where it left): rain through the flux surface (Eq. 39), drained walls
// (Eq. 36), and surfaces that hold a prescribed pressure (ponded, seepage faces, drying, held).
// The explicit engine integrates it step by step (server/physics/pore_water_account.h).
struct PoreWaterAccount {
  double rain = 0;
  double walls = 0;
  double surface = 0;
};

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
  PoreWaterAccount pore_water;
};

}  // namespace cascade
