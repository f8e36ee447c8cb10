// A run split over processes (issue 17), seen from outside as one Engine: every process builds the
// whole case, keeps its share (server/core/partition.h) and steps it; what the run reports (time
// step, lost particles, frames, the pore-water account) is reduced or gathered over the processes,
// so that every process sees the same answers and the runner's code is the same on each. Every
// method is collective: all processes call it, in the same order.
#pragma once

#include <memory>
#include <vector>

#include "server/core/engine.h"
#include "server/core/partition.h"

namespace cascade {

// The slabs of a run over `processes`: along the axis, not periodic, on which the moving particles
// spread farthest, cut so that each holds as many moving particles as the others (within one),
// with the halo that one pass reads around an owned particle or ghost node (halo_width).
Slabs slabs_for(const EngineConfig& config, const HostParticles& whole, int processes);

// The width of the halo: one list radius (2h and the skin, neighbour_list.h), within which an
// owned particle's list and a ghost node's search (the same radius) find their neighbours, plus
// the skin, by which particles may move between rebuilds of the halo. Each pass's results reach
// the copies from their owners before a later pass reads them (Simulation::evaluate_rates), so
// one radius suffices for the whole evaluation.
double halo_width(const EngineConfig& config);

class DistributedEngine final : public Engine {
 public:
  // `whole`: the case's particle set, the same on every process.
  DistributedEngine(const EngineConfig& config, const HostParticles& whole, Transport& transport);

  void step() override { share_->step(); }
  double time() const override { return share_->time(); }
  std::uint64_t step_count() const override { return share_->step_count(); }
  double last_dt() const override { return share_->last_dt(); }
  std::size_t particle_count() const override { return particles_; }
  std::size_t lost_particles() const override;
  std::size_t device_bytes() const override;
  FieldFrame frame() const override;  // the whole run's, on every process (a stage's criteria read it)
  // The whole run's on process 0; on the others a frame with the time and step and no particles.
  FieldFrame frame_at_process_0() const override;
  FieldFrame local_frame() const override;  // the share's, with the field "process"
  FieldFrame frame_block() const override;
  std::vector<std::vector<char>> parts_at_process_0(const SamplePart& part,
                                                    const std::vector<char>& request) const override;
  const char* device_name() const override { return share_->device_name(); }
  void set_forcing(const HydraulicForcing& forcing) override { share_->set_forcing(forcing); }
  HydraulicForcing forcing() const override { return share_->forcing(); }
  void restart_clock() override { share_->restart_clock(); }
  // The whole run's state, on every process, its particles in id order: what one process's
  // engine restores, and what a split run over any number of processes restores.
  EngineState state() const override;
  // The whole run's state on process 0, an empty one on the others (a split server's other
  // processes keep no checkpoint).
  EngineState state_at_process_0() const;
  // A state of the same case taken at any number of processes (rows in any order): the slabs are
  // cut again at the state's positions and every process takes its share of it.
  void restore(const EngineState& state) override;
  std::unique_ptr<Engine> clone() const override { refuse("a fork"); }
  PoreWaterAccount pore_water_account() const override;
  void set_relaxation(double local_damping) override { share_->set_relaxation(local_damping); }
  Equilibrium equilibrium() const override { return share_->equilibrium(); }
  void refresh_seepage() override { share_->refresh_seepage(); }
  void zero_velocities() override { share_->zero_velocities(); }
  LoadBalance load_balance() const override { return share_->load_balance(); }  // the same on every process

  const Slabs& slabs() const { return slabs_; }
  std::size_t share_size() const { return share_->particle_count(); }  // owned, copies and dummies held
  std::vector<std::size_t> share_sizes() const;                        // of every process, by process

 private:
  [[noreturn]] static void refuse(const char* what);
  std::unique_ptr<Engine> start_share(const HostParticles& whole, const EngineState* checkpoint);
  enum class FrameTo { every_process, process_0, id_blocks };
  FieldFrame gather_frame(FrameTo to) const;
  EngineState gather_state(bool everywhere) const;

  EngineConfig config_;
  Transport& transport_;
  Slabs slabs_;
  std::size_t particles_ = 0;
  std::unique_ptr<Engine> share_;
};

}  // namespace cascade
