// A run split over several processes (issue 17): each process owns the moving particles of one
// slab of the domain along one axis and holds copies of the others' particles within a halo
// around its slab, refreshed from their owners at the half step and the end of every step. The
// engine sees the other processes only through Transport (server/parallel/ implements it with
// MPI), so that no physics header and no part of the engine depends on MPI.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "server/core/engine_state.h"

namespace cascade {

// Message passing between the processes of one run. Every call is collective: all processes make
// it, in the same order.
class Transport {
 public:
  virtual ~Transport() = default;
  virtual int processes() const = 0;
  virtual int process() const = 0;  // this one, 0 .. processes() − 1
  virtual double minimum(double value) = 0;
  virtual double maximum(double value) = 0;
  virtual double sum(double value) = 0;
  // Sends send[r] to each process r (an empty message where there is nothing) and returns what
  // each process sent to this one, indexed by sender.
  virtual std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& send) = 0;
};

// The slabs: process r owns the moving particles with cut[r] <= x[axis] < cut[r + 1] (the first
// and last slabs reach past the domain), and holds every particle within `halo` of its slab.
struct Slabs {
  int axis = 0;
  std::vector<double> cut;  // processes + 1 entries, the first −∞ and the last +∞
  double halo = 0;          // width of the halo (m)

  int processes() const { return int(cut.size()) - 1; }
  int owner_of(double x) const {
    int r = 0;
    while (r + 1 < processes() && x >= cut[r + 1]) ++r;
    return r;
  }
  // Distance from x to slab r along the axis: 0 inside.
  double distance_to(int r, double x) const {
    if (x < cut[r]) return cut[r] - x;
    if (x >= cut[r + 1]) return x - cut[r + 1];
    return 0.0;
  }
};

// What a process's engine needs to know of the split: its transport, the slabs, and for each of
// its particles (in the order of the HostParticles it is built from) the particle's id in the
// whole run and the process that owns it. The positions of the whole run by id, for the soil's
// displacement (Simulation::initial_position_).
struct PartitionSetup {
  Transport* transport = nullptr;
  Slabs slabs;
  std::vector<std::uint32_t> global_id;
  std::vector<std::uint32_t> owner;
  bool soil = false;                     // the run has soil particles (some process may hold none)
  std::vector<double> initial_position;  // whole run, by id: N × 3 (empty without soil)
  // A share that starts from a checkpoint (DistributedEngine::restore): the checkpoint's rows of
  // the particles above, in the same order, with this process's part of the pore-water account.
  const EngineState* start = nullptr;
};

}  // namespace cascade
