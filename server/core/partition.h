// A run split over several processes (issue 17): each process owns the moving particles of one
// slab of the domain along one axis, and the dummies whose ghost nodes lie in it, and holds
// copies of the others' particles within a halo of one neighbour-list radius (2h and the skin)
// around its slab. The copies take their owners' values at the half step and the end of every
// step, and each pass whose results a neighbour reads sends them from the owners to the copies
// (Simulation::evaluate_rates). The engine sees the other processes only through Transport
// (server/parallel/ implements it with MPI), so that no physics header and no part of the engine
// depends on MPI.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
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

  // Bytes that this process writes into a file at an offset.
  struct FilePiece {
    std::uint64_t offset = 0;
    const void* bytes = nullptr;
    std::size_t size = 0;
  };
  // Writes every process's pieces into the existing file `path`, all processes at once (pieces must
  // not overlap; the file is neither created nor truncated). Throws std::runtime_error, naming the
  // file, where this process could not; the caller agrees on the outcome with the others.
  virtual void write_pieces(const std::string& path, const std::vector<FilePiece>& pieces) = 0;
};

// The slabs: process r owns the moving particles with cut[r] <= x[axis] < cut[r + 1] (the first
// and last slabs reach past the domain) and the dummies whose ghost nodes lie there: the grid
// around a ghost node, from which its dummy's values are interpolated (Eqs. 30-35), then lies
// within r's halo. r holds every particle within `halo` of its slab, and the dummies it owns.
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
  // Whether process r holds the dummy at x with its ghost node at ghost_x (both along the axis).
  bool holds_dummy(int r, double x, double ghost_x) const { return owner_of(ghost_x) == r || distance_to(r, x) < halo; }
  // Distance from x to slab r along the axis: 0 inside.
  double distance_to(int r, double x) const {
    if (x < cut[r]) return cut[r] - x;
    if (x >= cut[r + 1]) return x - cut[r + 1];
    return 0.0;
  }
};

// How evenly the processes share the work, measured at every neighbour-list rebuild: a process's
// work is the number of list entries of the particles it owns (the pairs its interaction passes
// visit, counted by the build; deterministic, unlike a timing, so that the run is), the imbalance
// the largest work over the mean. Above kRepartitionImbalance the slabs are cut again where the
// work is even (balanced_cuts) and the particles move to their new owners at once.
inline constexpr double kRepartitionImbalance = 1.1;  // issue 17: the slowest process 10% above the mean

struct LoadBalance {
  struct Rebuild {
    std::uint64_t step = 0;
    double time = 0;
    double imbalance = 1;
    bool repartitioned = false;  // the slabs were cut again at this rebuild (the imbalance is after it)
  };
  std::vector<Rebuild> rebuilds;

  double last() const { return rebuilds.empty() ? 1.0 : rebuilds.back().imbalance; }
  double largest() const {
    double l = 1;
    for (const auto& r : rebuilds) l = std::max(l, r.imbalance);
    return l;
  }
  double mean() const {
    double sum = 0;
    for (const auto& r : rebuilds) sum += r.imbalance;
    return rebuilds.empty() ? 1.0 : sum / double(rebuilds.size());
  }
  std::size_t repartitions() const {
    std::size_t n = 0;
    for (const auto& r : rebuilds) n += r.repartitioned;
    return n;
  }
};

// The cuts that give each of `processes` slabs an equal part of the work in `histogram`, whose
// bins split [low, high] evenly (linear within a bin).
inline std::vector<double> balanced_cuts(const std::vector<double>& histogram, double low, double high, int processes) {
  std::vector<double> cut(processes + 1, 0.0);
  cut.front() = -std::numeric_limits<double>::infinity();
  cut.back() = std::numeric_limits<double>::infinity();
  double total = 0;
  for (double w : histogram) total += w;
  const double width = (high - low) / double(histogram.size());
  std::size_t bin = 0;
  double below = 0;  // work in the bins before `bin`
  for (int r = 1; r < processes; ++r) {
    const double target = total * double(r) / double(processes);
    while (bin + 1 < histogram.size() && below + histogram[bin] < target) below += histogram[bin++];
    const double inside = histogram[bin] > 0 ? std::clamp((target - below) / histogram[bin], 0.0, 1.0) : 0.0;
    cut[r] = std::max(cut[r - 1], low + (double(bin) + inside) * width);
  }
  return cut;
}

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
