// A run as a sequence of stages (ScenarioSpec.stages; docs/physics.md, "Stages"): the geostatic
// start (the dynamic engine with local damping, Engine::set_relaxation), the implicit pore-water
// stage and the dynamic (explicit u-w-p) stage, on one set of particle fields. StagedEngine is an Engine: the runner and the server step it, query it,
// checkpoint it and steer its forcing as they do the dynamic engine, and read its stage switches
// (Engine::take_stage_changes) to report them.
//
// The dynamic engine holds the particle fields in every stage. The pore-water stage takes them
// (Engine::state) when it begins, advances the pore pressure, saturation and effective stress with
// its own implicit steps (quasistatic/implicit_pore_water.h) and hands them back after each step
// (Engine::restore) when frames, states or the next stage need them; the skeleton does not move
// in it. One implicit step is one step of the run's step count.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "server/core/engine.h"
#include "server/quasistatic/implicit_pore_water.h"
#include "server/solver/yield_band.h"

namespace cascade {

enum class StageKind { geostatic, pore_water, dynamic };

struct GeostaticCriteria {
  double force_ratio = 1e-4;     // unbalanced-force ratio (Engine::equilibrium)
  double speed = 1e-4;           // m/s
  double local_damping = 0.8;    // Cundall's coefficient
  std::uint64_t max_steps = 1000000;
};

// StageEnd.motion (scenario.proto): a trial of the dynamic engine from the stage's state.
struct MotionTrial {
  double speed = 0.1;     // m/s
  double duration = 1.0;  // s
  double interval = 0;    // s between trials; 0: after every implicit step
};

struct StagePlan {
  StageKind kind = StageKind::dynamic;
  std::string name;
  std::optional<double> end_time;  // s
  YieldBandCriterion yield_band;   // pore-water stage
  std::optional<MotionTrial> motion;  // pore-water stage
  GeostaticCriteria geostatic;
  ImplicitPoreWaterSettings pore_water;
};

class StagedEngine final : public Engine {
 public:
  // `forcing_times`: the times at which the case's forcing changes (its rain series); an implicit
  // step ends at each, so that a change applies from its own time.
  StagedEngine(std::unique_ptr<Engine> dynamic, const EngineConfig& config, std::vector<StagePlan> plan,
               std::vector<double> forcing_times);

  void step() override;
  double time() const override { return unsynced_ ? pore_water_state_.time : dynamic_->time(); }
  std::uint64_t step_count() const override { return unsynced_ ? pore_water_state_.steps : dynamic_->step_count(); }
  double last_dt() const override { return unsynced_ ? pore_water_state_.last_dt : dynamic_->last_dt(); }
  std::size_t particle_count() const override { return dynamic_->particle_count(); }
  std::size_t lost_particles() const override { return dynamic_->lost_particles(); }
  std::size_t device_bytes() const override { return dynamic_->device_bytes(); }
  FieldFrame frame() const override {
    sync();
    return dynamic_->frame();
  }
  FieldFrame frame_at_process_0() const override {
    sync();
    return dynamic_->frame_at_process_0();
  }
  FieldFrame local_frame() const override {
    sync();
    return dynamic_->local_frame();
  }
  FieldFrame frame_block() const override {
    sync();
    return dynamic_->frame_block();
  }
  std::vector<std::vector<char>> parts_at_process_0(const SamplePart& part,
                                                    const std::vector<char>& request) const override {
    sync();
    return dynamic_->parts_at_process_0(part, request);
  }
  const char* device_name() const override { return dynamic_->device_name(); }
  PoreWaterAccount pore_water_account() const override {
    return unsynced_ ? pore_water_state_.pore_water : dynamic_->pore_water_account();
  }
  void set_forcing(const HydraulicForcing& forcing) override { dynamic_->set_forcing(forcing); }
  HydraulicForcing forcing() const override { return dynamic_->forcing(); }
  void restart_clock() override { dynamic_->restart_clock(); }
  void set_relaxation(double local_damping) override { dynamic_->set_relaxation(local_damping); }
  Equilibrium equilibrium() const override { return dynamic_->equilibrium(); }
  void zero_velocities() override { dynamic_->zero_velocities(); }
  EngineState state() const override;
  void restore(const EngineState& state) override;
  std::unique_ptr<Engine> clone() const override;

  int stage() const override { return current_; }
  std::vector<StageChange> take_stage_changes() override;
  void advance_stage(const std::string& caller) override;

  // The implicit stage's water balance since it began (zeros outside it).
  WaterBalance water_balance() const { return pore_water_ ? pore_water_->balance() : WaterBalance{}; }

 private:
  // Hands the implicit stage's fields to the dynamic engine, which frames and states read.
  void sync() const;
  void enter(int stage, const std::string& reason);
  void pore_water_step();
  // One step of dynamic relaxation; at equilibrium the damping goes, the velocities are zeroed,
  // the clock restarts at t = 0 and the next stage begins.
  void geostatic_step();
  std::optional<std::string> stage_end_reached();
  // StageEnd.motion: lets the dynamic engine run `trial.duration` from the current state, then puts
  // the state back; the reason to switch if some soil reached trial.speed.
  std::optional<std::string> slope_moves(const MotionTrial& trial);
  double next_forcing_time() const;

  std::unique_ptr<Engine> dynamic_;
  const EngineConfig config_;
  const std::vector<StagePlan> plan_;
  const std::vector<double> forcing_times_;
  int current_ = 0;
  std::vector<StageChange> changes_;
  bool started_ = false;
  std::uint64_t geostatic_steps_ = 0;
  double last_trial_time_ = -std::numeric_limits<double>::infinity();
  std::uint64_t trials_ = 0;  // motion trials in this stage
  std::unique_ptr<ImplicitPoreWater> pore_water_;
  mutable EngineState pore_water_state_;  // the fields the implicit stage advances
  mutable bool unsynced_ = false; // they are ahead of the dynamic engine's
};

}  // namespace cascade
