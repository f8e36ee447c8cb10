#include "server/solver/staged_engine.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "server/core/types.h"

namespace cascade {

namespace {

std::string text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// The pore-water stage's numbers that a checkpoint carries (EngineState::stage_values).
constexpr const char* kNextDt = "pore_water.next_dt";
constexpr const char* kGeostaticSteps = "geostatic.steps";
constexpr const char* kLastTrialTime = "motion.last_trial_time";
constexpr const char* kTrials = "motion.trials";

}  // namespace

StagedEngine::StagedEngine(std::unique_ptr<Engine> dynamic, const EngineConfig& config, std::vector<StagePlan> plan,
                           std::vector<double> forcing_times)
    : dynamic_(std::move(dynamic)), config_(config), plan_(std::move(plan)), forcing_times_(std::move(forcing_times)) {
  if (plan_.empty()) throw std::invalid_argument("a staged run needs at least one stage");
  enter(0, "the run starts");
}

void StagedEngine::sync() const {
  if (!unsynced_) return;
  pore_water_state_.forcing = dynamic_->forcing();  // as steered since the last step
  dynamic_->restore(pore_water_state_);
  dynamic_->refresh_seepage();  // the implicit stage moves no seepage array: its frames need one
  unsynced_ = false;
}

void StagedEngine::enter(int stage, const std::string& reason) {
  sync();
  const StagePlan& next = plan_.at(std::size_t(stage));
  StageChange change;
  change.time = dynamic_->time();
  change.step = dynamic_->step_count();
  change.from = started_ ? current_ : -1;
  started_ = true;
  change.from_name = change.from < 0 ? "" : plan_[std::size_t(current_)].name;
  change.to = stage;
  change.to_name = next.name;
  change.reason = reason;
  if (pore_water_) {
    const WaterBalance& b = pore_water_->balance();
    change.reason += "; the stage's water balance (m^" + std::to_string(config_.dimensions) + "): rain " +
                     text(b.rain) + ", infiltration " + text(b.infiltration) + ", runoff " + text(b.runoff) +
                     ", exfiltration " + text(b.exfiltration) + ", walls " + text(b.walls) + ", free water " +
                     text(b.free_water) + ", storage change " + text(b.storage) + ", error " + text(b.error());
  }
  changes_.push_back(change);
  current_ = stage;
  pore_water_.reset();
  last_trial_time_ = -std::numeric_limits<double>::infinity();
  trials_ = 0;
  if (next.kind == StageKind::geostatic) {
    geostatic_steps_ = 0;
    dynamic_->set_relaxation(next.geostatic.local_damping);
  }
  if (next.kind == StageKind::pore_water) {
    pore_water_state_ = dynamic_->state();
    pore_water_ = std::make_unique<ImplicitPoreWater>(config_, pore_water_state_, next.pore_water);
  }
}

void StagedEngine::step() {
  const StagePlan& stage = plan_[std::size_t(current_)];
  if (stage.kind == StageKind::geostatic) return geostatic_step();
  if (stage.kind == StageKind::pore_water) pore_water_step();
  else dynamic_->step();
  if (std::size_t(current_) + 1 >= plan_.size()) return;  // the last stage runs to the end
  if (const auto reason = stage_end_reached()) enter(current_ + 1, *reason);
}

void StagedEngine::geostatic_step() {
  const GeostaticCriteria& criteria = plan_[std::size_t(current_)].geostatic;
  dynamic_->step();
  ++geostatic_steps_;
  const Equilibrium e = dynamic_->equilibrium();
  if (e.force_ratio <= criteria.force_ratio && e.max_speed <= criteria.speed) {
    dynamic_->set_relaxation(0.0);
    dynamic_->zero_velocities();
    dynamic_->restart_clock();
    const std::string reason = "equilibrium after " + std::to_string(geostatic_steps_) +
                               " steps of dynamic relaxation: unbalanced-force ratio " + text(e.force_ratio) +
                               ", largest soil speed " + text(e.max_speed) + " m/s; the clock restarts at t = 0";
    if (std::size_t(current_) + 1 < plan_.size()) enter(current_ + 1, reason);
    return;
  }
  if (geostatic_steps_ >= criteria.max_steps)
    throw SimulationFailure("the geostatic stage did not reach equilibrium in " + std::to_string(geostatic_steps_) +
                            " steps: unbalanced-force ratio " + text(e.force_ratio) + " (limit " +
                            text(criteria.force_ratio) + "), largest soil speed " + text(e.max_speed) +
                            " m/s (limit " + text(criteria.speed) + ")");
}

void StagedEngine::pore_water_step() {
  const StagePlan& stage = plan_[std::size_t(current_)];
  double limit = next_forcing_time() - time();
  if (stage.end_time) limit = std::min(limit, *stage.end_time - time());
  // A step never shorter than min_dt because of a target just ahead: it then reaches past it.
  limit = std::max(limit, stage.pore_water.min_dt);
  pore_water_state_.forcing = dynamic_->forcing();  // as steered since the last step
  pore_water_->step(pore_water_state_, pore_water_state_.forcing, limit);
  unsynced_ = true;
}

std::optional<std::string> StagedEngine::stage_end_reached() {
  const StagePlan& stage = plan_[std::size_t(current_)];
  if (stage.end_time && time() >= *stage.end_time * (1 - 1e-12))
    return "the stage's end time " + text(*stage.end_time) + " s";
  if (stage.kind == StageKind::pore_water && stage.yield_band.active()) {
    const std::string reached =
        yield_band_reached(measure_yield_band(frame(), stage.yield_band, config_.dp), stage.yield_band);
    if (!reached.empty()) return reached;
  }
  if (stage.kind == StageKind::pore_water && stage.motion &&
      time() >= last_trial_time_ + stage.motion->interval * (1 - 1e-12))
    return slope_moves(*stage.motion);
  return std::nullopt;
}

std::optional<std::string> StagedEngine::slope_moves(const MotionTrial& trial) {
  const FieldFrame f = frame();  // synced: the dynamic engine holds the stage's state
  const auto* ratio = f.find("yield_ratio");
  std::size_t yielded = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.phase[i] == std::uint8_t(Phase::soil) && ratio && ratio->values[i] >= 1.0) ++yielded;
  if (yielded == 0) return std::nullopt;  // nothing at yield: no mechanism, no trial
  last_trial_time_ = time();
  ++trials_;
  const EngineState before = dynamic_->state();
  while (dynamic_->time() < before.time + trial.duration) dynamic_->step();
  const double speed = dynamic_->equilibrium().max_speed;
  const std::uint64_t trial_steps = dynamic_->step_count() - before.steps;
  dynamic_->restore(before);
  if (!(speed >= trial.speed)) return std::nullopt;
  return "the slope moves: let go from this state, the dynamic engine brought soil to " + text(speed) + " m/s in " +
         text(trial.duration) + " s (" + std::to_string(trial_steps) + " steps; >= " + text(trial.speed) +
         " m/s); " + std::to_string(yielded) + " soil particles at yield ratio >= 1; trial " + std::to_string(trials_) +
         " of the stage";
}

double StagedEngine::next_forcing_time() const {
  const double now = time();
  for (const double t : forcing_times_)
    if (t > now * (1 + 1e-12) + 1e-12) return t;
  return std::numeric_limits<double>::infinity();
}

std::vector<StageChange> StagedEngine::take_stage_changes() {
  std::vector<StageChange> taken;
  taken.swap(changes_);
  return taken;
}

void StagedEngine::advance_stage(const std::string& caller) {
  if (std::size_t(current_) + 1 >= plan_.size())
    throw std::invalid_argument("the " + plan_[std::size_t(current_)].name + " stage is the run's last");
  // The caller's command is applied at a step boundary: the next step is the next stage's.
  enter(current_ + 1, "requested by " + caller);
}

EngineState StagedEngine::state() const {
  sync();
  EngineState s = dynamic_->state();
  s.stage = current_;
  if (pore_water_) s.stage_values[kNextDt] = pore_water_->next_dt();
  if (trials_ > 0) {
    s.stage_values[kLastTrialTime] = last_trial_time_;
    s.stage_values[kTrials] = double(trials_);
  }
  if (plan_[std::size_t(current_)].kind == StageKind::geostatic) s.stage_values[kGeostaticSteps] = double(geostatic_steps_);
  return s;
}

// The dynamic engine's clone, then this engine's stage and its numbers as restore() sets them from
// a state: the implicit stage's solver is rebuilt from the fields, as after a checkpoint.
std::unique_ptr<Engine> StagedEngine::clone() const {
  auto copy = std::make_unique<StagedEngine>(dynamic_->clone(), config_, plan_, forcing_times_);
  copy->restore(state());
  return copy;
}

void StagedEngine::restore(const EngineState& s) {
  if (s.stage < 0 || std::size_t(s.stage) >= plan_.size())
    throw std::invalid_argument("the state is of stage " + std::to_string(s.stage) + "; the case has " +
                                std::to_string(plan_.size()));
  dynamic_->restore(s);
  unsynced_ = false;
  current_ = s.stage;
  changes_.clear();  // the state's history replaces this engine's
  pore_water_.reset();
  const auto last_trial = s.stage_values.find(kLastTrialTime);
  const auto trials = s.stage_values.find(kTrials);
  last_trial_time_ = last_trial != s.stage_values.end() ? last_trial->second : -std::numeric_limits<double>::infinity();
  trials_ = trials != s.stage_values.end() ? std::uint64_t(trials->second) : 0;
  if (plan_[std::size_t(current_)].kind == StageKind::geostatic) {
    // The relaxation is the stage's, not the state's: on again, from the steps the state had.
    const auto steps = s.stage_values.find(kGeostaticSteps);
    geostatic_steps_ = steps != s.stage_values.end() ? std::uint64_t(steps->second) : 0;
    dynamic_->set_relaxation(plan_[std::size_t(current_)].geostatic.local_damping);
  } else {
    dynamic_->set_relaxation(0.0);
  }
  if (plan_[std::size_t(current_)].kind == StageKind::pore_water) {
    pore_water_state_ = dynamic_->state();
    pore_water_ = std::make_unique<ImplicitPoreWater>(config_, pore_water_state_, plan_[std::size_t(current_)].pore_water);
    const auto dt = s.stage_values.find(kNextDt);
    if (dt != s.stage_values.end()) pore_water_->set_next_dt(dt->second);
  }
}

}  // namespace cascade
