#include "server/service/session.h"

#include <omp.h>
#include <pthread.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

#include "server/core/free_cores.h"
#include "server/io/sample_parts.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/forcing_message.h"
#include "server/scenario/output_schedule.h"
#include "server/scenario/rain_series.h"
#include "server/scenario/stage_setup.h"

namespace cascade::service {

namespace {

// Energy and soil speed need a copy of every field: taken with the probe samples, and otherwise
// at most this often while running, so that their cost stays a small share of the steps'.
constexpr double kEnergySampleSeconds = 0.5;
// Window of the steps-per-second rate.
constexpr double kRateSeconds = 1.0;
// The runner's end test (clients/cli/run_command.cpp): the same step ends both runs.
constexpr double kEndSlack = 1e-12;

double wall_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

const char* state_word(v1::Simulation::State state) {
  switch (state) {
    case v1::Simulation::CREATED: return "created";
    case v1::Simulation::RUNNING: return "running";
    case v1::Simulation::PAUSED: return "paused";
    case v1::Simulation::COMPLETED: return "completed";
    case v1::Simulation::FAILED: return "failed";
    default: return "unspecified";
  }
}

// Reads back as the same double.
std::string exact_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::vector<std::string> names_of_probes(const v1::ScenarioSpec& spec) {
  std::vector<std::string> names;
  for (const auto& p : spec.probes()) names.push_back(p.name());
  return names;
}

std::vector<std::string> names_of_stages(const v1::ScenarioSpec& spec) {
  std::vector<std::string> names;
  for (const auto& plan : stage_plans(spec)) names.push_back(plan.name);
  if (names.empty()) names.push_back("dynamic");  // scenario.proto: no stages, one dynamic stage
  return names;
}

}  // namespace

struct Session::ScheduledForcing {
  v1::Forcing forcing;
  std::vector<std::string> mask;
  double effective_time = 0;
  std::string caller;
  Done done;
};

struct Session::Command {
  enum class Kind {
    start, pause, resume, step, run_until, update_forcing, advance_stage, query, tap_frames, checkpoint, fork
  };
  Kind kind;
  std::string caller;
  std::uint64_t steps = 0;
  double time = 0;
  ScheduledForcing forcing;
  std::optional<double> effective_time;
  Done done;
  FrameDone frame_done;
  std::weak_ptr<FrameTap> tap;
  CheckpointDone checkpoint_done;
  std::string reason;  // advance_stage; fork: the fork's name
  ForkDone fork_done;
  std::optional<v1::EventStop> event_stop;  // run_until
};

Session::Session(SessionConfig config)
    : restore_source_(std::exchange(config.restore, nullptr)),
      config_(std::move(config)),
      probe_names_(names_of_probes(config_.spec)),
      stage_names_(names_of_stages(config_.spec)) {
  status_.set_state(v1::Simulation::CREATED);
  status_.set_stage_name(stage_names_.front());
  forcing_ = forcing_message(config_.engine.forcing, config_.engine.dimensions);
  if (restore_source_) {  // published at once: the reply to RestoreCheckpoint shows where it is
    state_ = v1::Simulation::PAUSED;
    status_.set_state(state_);
    const Engine* clone = restore_source_->engine.get();  // a fork's
    const EngineState& restored = restore_source_->checkpoint.engine;
    const int stage = clone ? clone->stage() : restored.stage;
    status_.set_time(clone ? clone->time() : restored.time);
    status_.set_step(clone ? clone->step_count() : restored.steps);
    status_.set_dt(clone ? clone->last_dt() : restored.last_dt);
    status_.set_stage(std::uint32_t(stage));
    status_.set_stage_name(stage_names_.at(std::size_t(stage)));
    forcing_ = forcing_message(restored.forcing, config_.engine.dimensions);
    if (const auto& fork = restore_source_->fork) {  // a fork goes on from its parent's history
      events_ = fork->events;
      probe_samples_ = fork->probe_samples;
      forcing_ = fork->forcing;
    }
  }
  thread_ = std::thread([this] { run_loop(); });
}

Session::~Session() { stop("delete", "server"); }

// ---- RPC side: queue and return ----

void Session::enqueue(Command command) {
  {
    std::lock_guard lock(mutex_);
    if (!thread_ended_ && !stop_requested_) {
      queue_.push_back(std::move(command));
      wake_.notify_one();
      return;
    }
  }
  const grpc::Status gone(grpc::StatusCode::FAILED_PRECONDITION, "simulation " + config_.name + " is stopping");
  if (command.done) command.done({gone, 0, 0});
  if (command.frame_done) command.frame_done(gone, nullptr);
  if (command.checkpoint_done) command.checkpoint_done(gone, {});
  if (command.fork_done) command.fork_done(gone, nullptr);
}

void Session::start(const std::string& caller, Done done) {
  enqueue({Command::Kind::start, caller, 0, 0, {}, {}, std::move(done), {}});
}
void Session::pause(const std::string& caller, Done done) {
  enqueue({Command::Kind::pause, caller, 0, 0, {}, {}, std::move(done), {}});
}
void Session::resume(const std::string& caller, Done done) {
  enqueue({Command::Kind::resume, caller, 0, 0, {}, {}, std::move(done), {}});
}
void Session::step(std::uint64_t steps, const std::string& caller, Done done) {
  enqueue({Command::Kind::step, caller, steps, 0, {}, {}, std::move(done), {}});
}
void Session::run_until(double time, const std::string& caller, Done done, std::optional<v1::EventStop> stop) {
  Command command{Command::Kind::run_until, caller, 0, time, {}, {}, std::move(done), {}};
  command.event_stop = std::move(stop);
  enqueue(std::move(command));
}
void Session::update_forcing(const v1::Forcing& forcing, std::vector<std::string> mask,
                             std::optional<double> effective_time, const std::string& caller, Done done) {
  enqueue({Command::Kind::update_forcing, caller, 0, 0, {forcing, std::move(mask), 0, caller, nullptr}, effective_time,
           std::move(done), {}});
}
void Session::advance_stage(const std::string& reason, const std::string& caller, Done done) {
  Command command{Command::Kind::advance_stage, caller, 0, 0, {}, {}, std::move(done), {}};
  command.reason = reason;
  enqueue(std::move(command));
}
void Session::query(FrameDone done) {
  enqueue({Command::Kind::query, {}, 0, 0, {}, {}, {}, std::move(done)});
}

void Session::tap_frames(std::weak_ptr<FrameTap> tap) {
  enqueue({Command::Kind::tap_frames, {}, 0, 0, {}, {}, {}, {}, std::move(tap)});
}

void Session::checkpoint(const std::string& caller, CheckpointDone done) {
  Command command{Command::Kind::checkpoint, caller, 0, 0, {}, {}, {}, {}};
  command.checkpoint_done = std::move(done);
  enqueue(std::move(command));
}

void Session::fork(const std::string& fork_name, const std::string& caller, ForkDone done) {
  Command command{Command::Kind::fork, caller, 0, 0, {}, {}, {}, {}};
  command.reason = fork_name;
  command.fork_done = std::move(done);
  enqueue(std::move(command));
}

void Session::stop(const std::string& reason, const std::string& caller, bool checkpoint_first) {
  {
    std::lock_guard lock(mutex_);
    if (!stop_requested_) {
      stop_requested_ = true;
      stop_reason_ = reason;
      stop_caller_ = caller;
      checkpoint_on_stop_ = checkpoint_first;
    }
    wake_.notify_one();
  }
  std::lock_guard join_lock(join_mutex_);
  if (thread_.joinable()) thread_.join();
}

v1::Simulation Session::describe() const {
  v1::Simulation s;
  s.set_name(config_.name);
  s.set_case_name(config_.spec.name());
  s.set_end_time(config_.spec.end_time());
  s.set_particle_count(config_.particles->size());
  s.set_device(config_.engine.device == Device::cuda ? "cuda" : "cpu");
  s.set_journal_path((config_.directory / "journal.jsonl").string());
  std::lock_guard lock(mutex_);
  s.set_state(state_);
  s.set_failure_reason(failure_reason_);
  *s.mutable_status() = status_;
  *s.mutable_forcing() = forcing_;
  return s;
}

v1::Status Session::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

bool Session::stopped() const {
  std::lock_guard lock(mutex_);
  return thread_ended_ || state_ == v1::Simulation::COMPLETED || state_ == v1::Simulation::FAILED;
}

std::vector<v1::ProbeSample> Session::probe_samples(double since_time) const {
  std::lock_guard lock(mutex_);
  const auto first = std::lower_bound(probe_samples_.begin(), probe_samples_.end(), since_time,
                                      [](const v1::ProbeSample& s, double t) { return s.time() < t; });
  return {first, probe_samples_.end()};
}

std::vector<v1::Event> Session::events(std::size_t first) const {
  std::lock_guard lock(mutex_);
  if (first >= events_.size()) return {};
  return {events_.begin() + std::ptrdiff_t(first), events_.end()};
}

// ---- the solver thread ----

Session::Outcome Session::here(grpc::Status status) const {
  return {std::move(status), engine_ ? engine_->step_count() : 0, engine_ ? engine_->time() : 0.0};
}

void Session::run_loop() {
  // Named so that an operator (top -H, ps -L) and the load test (tests/cli/test_server_load.py) can
  // tell the thread that steps a simulation from the request handlers; at most 15 characters.
  pthread_setname_np(pthread_self(), "cascade-solver");
  // Without a thread count the team takes its share of the cores that other processes leave free,
  // among this server's simulations that are stepping (free_cores.h).
  std::optional<CoreShare::Running> stepping;
  int team = omp_get_max_threads();
  auto size_team = [&] {
    const int threads = config_.threads > 0 ? config_.threads : CoreShare::of_this_process().threads_per_simulation();
    if (threads != team) omp_set_num_threads(team = threads);
  };
  stepping.emplace();  // the initialisation stage steps too
  size_team();
  initialise();
  stepping.reset();
  for (;;) {
    std::deque<Command> commands;
    // state_ is written by this thread only, so it reads it without the lock. While the simulation
    // runs, this thread does not wait for the lock either: a request handler that holds it and has
    // lost its core to other threads would stall the step for the rest of its time slice (under 32
    // clients the solver thread was asleep 12% of the time, bench/server_clients.py). The commands
    // then wait for a later step; a stop is seen at once (stop_requested_ is atomic).
    if (state_ == v1::Simulation::RUNNING) {
      if (stop_requested_) break;
      std::unique_lock lock(mutex_, std::try_to_lock);
      if (lock.owns_lock()) commands.swap(queue_);
    } else {
      stepping.reset();  // an idle simulation takes no share
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_requested_ || !queue_.empty() || state_ == v1::Simulation::RUNNING; });
      if (stop_requested_) break;
      commands.swap(queue_);
    }
    for (auto& command : commands) {
      try {
        apply(command);
      } catch (const std::exception& e) {  // the journal could not be written: nothing may go on
        stop_running(v1::Simulation::FAILED, e.what());
        const grpc::Status failed(grpc::StatusCode::INTERNAL, e.what());
        if (command.done) command.done(here(failed));
        if (command.frame_done) command.frame_done(failed, nullptr);
        if (command.checkpoint_done) command.checkpoint_done(failed, {});
        if (command.fork_done) command.fork_done(failed, nullptr);
      }
    }
    if (state_ != v1::Simulation::RUNNING || stop_requested_) continue;
    if (!stepping) stepping.emplace();
    size_team();
    try {
      advance();
    } catch (const std::exception& e) {  // the journal could not be written: nothing may go on
      stop_running(v1::Simulation::FAILED, e.what());
    }
  }

  // Stopping: a running simulation pauses at this boundary; everything still waiting is refused.
  const grpc::Status refused(grpc::StatusCode::ABORTED, "simulation " + config_.name + " stopped (" + stop_reason_ + ")");
  std::deque<Command> left;
  bool worth_keeping = false;
  {
    std::lock_guard lock(mutex_);
    worth_keeping = engine_ && (state_ == v1::Simulation::RUNNING || state_ == v1::Simulation::PAUSED);
    if (state_ == v1::Simulation::RUNNING) state_ = v1::Simulation::PAUSED;
    left.swap(queue_);
  }
  if (checkpoint_on_stop_ && worth_keeping) {
    try {
      take_checkpoint(stop_caller_);
    } catch (const std::exception& e) {  // the process goes on stopping; the journal says how far it got
      std::fprintf(stderr, "cascade-server: %s: no checkpoint: %s\n", config_.name.c_str(), e.what());
    }
  }
  v1::JournalEntry entry;
  entry.set_command(stop_reason_);
  entry.set_caller(stop_caller_);
  journal(std::move(entry));
  publish_status();
  for (auto& command : left) {
    if (command.done) command.done(here(refused));
    if (command.frame_done) command.frame_done(refused, nullptr);
    if (command.checkpoint_done) command.checkpoint_done(refused, {});
    if (command.fork_done) command.fork_done(refused, nullptr);
  }
  for (auto& change : scheduled_) change.done(here(refused));
  for (auto& waiter : target_waiters_) waiter(here());
  std::lock_guard lock(mutex_);
  thread_ended_ = true;
}

void Session::initialise() {
  if (restore_source_) return restore();
  try {
    journal_ = std::make_unique<JournalWriter>(config_.directory / "journal.jsonl");
    v1::JournalEntry entry;
    entry.set_command("create");
    entry.set_caller(config_.caller);
    entry.set_case_name(config_.spec.name());
    journal(std::move(entry));
    engine_ = make_case_engine(config_.spec, config_.engine, *config_.particles, config_.make_engine);
    probes_ = std::make_unique<ProbeSampler>(config_.spec, config_.engine.h,
                                             config_.engine.water_density * std::pow(config_.engine.dp, config_.engine.dimensions));
    cascade_events_ = std::make_unique<CascadeEventDetector>(config_.spec, config_.engine.h, probes_->names());
    const std::uint64_t steps = run_initialisation(config_.spec, *engine_);
    if (steps > 0) add_event("initialisation", std::to_string(steps) + " steps; the clock restarts at t = 0", "server");
    rate_wall_ = wall_now();
    rate_step_ = engine_->step_count();
    report_stage_changes("solver");
    sample_outputs(true);
    add_event("state", "created", config_.caller);
  } catch (const std::exception& e) {
    engine_.reset();  // nothing to step: every later command is refused by its state check
    stop_running(v1::Simulation::FAILED, std::string("set-up failed: ") + e.what());
  }
  publish_status();
}

// A COMPLETED or FAILED simulation refuses a command that would change it: FAILED_PRECONDITION.
bool Session::refused_when_ended(const Done& done, const char* what) {
  v1::Simulation::State state;
  {
    std::lock_guard lock(mutex_);
    state = state_;
  }
  if (state != v1::Simulation::COMPLETED && state != v1::Simulation::FAILED) return false;
  done(here({grpc::StatusCode::FAILED_PRECONDITION, config_.name + " is " + state_word(state) + ": " + what}));
  return true;
}

bool Session::transition(const Done& done, std::initializer_list<v1::Simulation::State> from, const char* command) {
  v1::Simulation::State state;
  {
    std::lock_guard lock(mutex_);
    state = state_;
  }
  if (std::find(from.begin(), from.end(), state) != from.end()) return true;
  done(here({grpc::StatusCode::FAILED_PRECONDITION,
             std::string(command) + " needs a simulation that is " +
                 (from.size() == 1 ? state_word(*from.begin()) : "created or paused") + "; " + config_.name + " is " +
                 state_word(state)}));
  return false;
}

void Session::apply(Command& c) {
  auto entry_for = [&](const char* command, const std::string& detail) {
    v1::JournalEntry entry;
    entry.set_command(command);
    entry.set_caller(c.caller);
    entry.set_detail(detail);
    return entry;
  };
  auto run = [&](const char* command, const std::string& detail) {
    journal(entry_for(command, detail));
    {
      std::lock_guard lock(mutex_);
      state_ = v1::Simulation::RUNNING;
    }
    add_event("state", std::string("running (") + command + (detail.empty() ? "" : " " + detail) + ")", c.caller);
    publish_status();
  };
  switch (c.kind) {
    case Command::Kind::start:
      if (!transition(c.done, {v1::Simulation::CREATED}, "start")) return;
      stop_step_.reset(), stop_time_.reset(), stop_event_.reset();
      run("start", "");
      c.done(here());
      return;
    case Command::Kind::resume:
      if (!transition(c.done, {v1::Simulation::PAUSED}, "resume")) return;
      stop_step_.reset(), stop_time_.reset(), stop_event_.reset();
      run("resume", "");
      c.done(here());
      return;
    case Command::Kind::step:
      if (!transition(c.done, {v1::Simulation::CREATED, v1::Simulation::PAUSED}, "step")) return;
      stop_step_ = engine_->step_count() + c.steps, stop_time_.reset(), stop_event_.reset();
      run("step", std::to_string(c.steps));
      target_waiters_.push_back(std::move(c.done));
      return;
    case Command::Kind::run_until:
      if (!transition(c.done, {v1::Simulation::CREATED, v1::Simulation::PAUSED}, "run_until")) return;
      if (!(c.time > engine_->time())) {
        c.done(here({grpc::StatusCode::FAILED_PRECONDITION,
                     "time: " + std::to_string(c.time) + " s is not after the simulation's time " +
                         std::to_string(engine_->time()) + " s"}));
        return;
      }
      stop_time_ = c.time, stop_step_.reset();
      stop_event_ = c.event_stop;
      run("run_until", exact_text(c.time) + (stop_event_ ? " or " + exact_text(stop_event_->seconds()) + " s after " +
                                                               stop_event_->kind()
                                                         : ""));
      target_waiters_.push_back(std::move(c.done));
      return;
    case Command::Kind::pause: {
      if (!transition(c.done, {v1::Simulation::RUNNING}, "pause")) return;
      journal(entry_for("pause", ""));
      stop_running(v1::Simulation::PAUSED, "paused");
      c.done(here());
      return;
    }
    case Command::Kind::update_forcing: {
      if (refused_when_ended(c.done, "its forcing can no longer change")) return;
      c.forcing.done = std::move(c.done);
      if (c.effective_time && *c.effective_time > engine_->time()) {
        c.forcing.effective_time = *c.effective_time;
        scheduled_.push_back(std::move(c.forcing));
        return;
      }
      apply_forcing_change(c.forcing);
      return;
    }
    case Command::Kind::advance_stage: {
      if (refused_when_ended(c.done, "its stage can no longer change")) return;
      try {
        engine_->advance_stage(c.caller);
      } catch (const std::invalid_argument& e) {
        c.done(here({grpc::StatusCode::FAILED_PRECONDITION, config_.name + ": " + e.what()}));
        return;
      }
      journal(entry_for("advance_stage", c.reason));
      report_stage_changes(c.caller);
      publish_status();
      c.done(here());
      return;
    }
    case Command::Kind::query:
      if (!engine_) {
        c.frame_done({grpc::StatusCode::FAILED_PRECONDITION, config_.name + " has no engine: " + failure_reason_},
                     nullptr);
        return;
      }
      c.frame_done(grpc::Status::OK, std::make_shared<const FieldFrame>(engine_->frame()));
      return;
    case Command::Kind::tap_frames:
      if (!engine_) return;  // the simulation has failed: the tap's stream ends when it sees so
      if (auto tap = c.tap.lock()) tap->take_frame(std::make_shared<const FieldFrame>(engine_->frame()));
      frame_taps_.push_back(std::move(c.tap));
      return;
    case Command::Kind::checkpoint:
    case Command::Kind::fork: {
      std::unique_lock lock(mutex_);
      if (!engine_ || state_ == v1::Simulation::FAILED) {
        const grpc::Status failed(grpc::StatusCode::FAILED_PRECONDITION,
                                  config_.name + " has failed (" + failure_reason_ + "): its state cannot be continued");
        lock.unlock();
        if (c.checkpoint_done) c.checkpoint_done(failed, {});
        if (c.fork_done) c.fork_done(failed, nullptr);
        return;
      }
      lock.unlock();
      if (c.kind == Command::Kind::checkpoint) c.checkpoint_done(grpc::Status::OK, take_checkpoint(c.caller));
      else c.fork_done(grpc::Status::OK, take_fork(c.reason, c.caller));
      return;
    }
  }
}

void Session::apply_forcing_change(const ScheduledForcing& change) {
  const HydraulicForcing old_forcing = engine_->forcing();
  const int dims = config_.engine.dimensions;
  HydraulicForcing new_forcing = updated_forcing(old_forcing, change.forcing, change.mask, dims);
  v1::JournalEntry entry;
  entry.set_command("update_forcing");
  entry.set_caller(change.caller);
  for (const auto& field : change.mask) entry.add_update_mask(field);
  *entry.mutable_old_forcing() = forcing_now();
  rain_.steer(change.mask, change.forcing);  // a factor sets the intensity at once
  if (const auto due = rain_.due(config_.spec, engine_->time(), new_forcing.rainfall_intensity))
    new_forcing.rainfall_intensity = *due;
  engine_->set_forcing(new_forcing);
  *entry.mutable_new_forcing() = forcing_now();
  journal(entry);
  {
    std::lock_guard lock(mutex_);
    forcing_ = entry.new_forcing();
  }
  std::string what;
  for (const auto& field : change.mask) what += (what.empty() ? "" : ", ") + field;
  add_event("forcing", what + ": " + entry.old_forcing().ShortDebugString() + " -> " + entry.new_forcing().ShortDebugString(),
            change.caller);
  change.done(here());
}

v1::Forcing Session::forcing_now() const {
  v1::Forcing forcing = forcing_message(engine_->forcing(), config_.engine.dimensions);
  if (const auto factor = rain_.factor()) forcing.mutable_rainfall()->set_factor(*factor);
  return forcing;
}

void Session::advance() {
  // Scheduled forcing changes that are due, in their order of arrival.
  for (auto it = scheduled_.begin(); it != scheduled_.end();) {
    if (it->effective_time <= engine_->time()) {
      apply_forcing_change(*it);
      it = scheduled_.erase(it);
    } else {
      ++it;
    }
  }
  if (const auto due = rain_.due(config_.spec, *engine_)) {
    HydraulicForcing next = engine_->forcing();
    next.rainfall_intensity = *due;
    engine_->set_forcing(next);
    {
      std::lock_guard lock(mutex_);
      forcing_ = forcing_now();
    }
    add_event("forcing",
              "rain series: rainfall.intensity " + std::to_string(*due) + " m/s" + rain_series_origin(config_.spec) +
                  (rain_.factor() ? " (factor " + exact_text(*rain_.factor()) + ")" : ""),
              "case");
  }
  try {
    engine_->step();
  } catch (const std::exception& e) {
    v1::JournalEntry entry;
    entry.set_command("failed");
    entry.set_caller("server");
    entry.set_detail(e.what());
    journal(std::move(entry));
    stop_running(v1::Simulation::FAILED, e.what());
    return;
  }
  report_stage_changes("solver");
  if (engine_->lost_particles() != lost_particles_) {
    add_event("particles_lost",
              std::to_string(engine_->lost_particles() - lost_particles_) + " particles left the domain (" +
                  std::to_string(engine_->lost_particles()) + " in all)",
              "server");
    lost_particles_ = engine_->lost_particles();
  }
  sample_outputs(false);
  feed_taps();
  reach_targets();
  publish_status(/*wait=*/false);
}

void Session::feed_taps() {
  std::shared_ptr<const FieldFrame> frame;  // one copy for every tap that wants this step's
  for (auto it = frame_taps_.begin(); it != frame_taps_.end();) {
    const auto tap = it->lock();
    if (!tap) {
      it = frame_taps_.erase(it);
      continue;
    }
    if (tap->wants_frame(engine_->time())) {
      if (!frame) frame = std::make_shared<const FieldFrame>(engine_->frame());
      tap->take_frame(frame);
    }
    ++it;
  }
}

void Session::reach_targets() {
  const double end = config_.spec.end_time();
  if (engine_->time() >= end * (1 - kEndSlack)) {
    v1::JournalEntry entry;
    entry.set_command("completed");
    entry.set_caller("server");
    journal(std::move(entry));
    sample_outputs(true);
    stop_running(v1::Simulation::COMPLETED, "completed at the end time");
  } else if ((stop_step_ && engine_->step_count() >= *stop_step_) || (stop_time_ && engine_->time() >= *stop_time_)) {
    sample_outputs(true);
    stop_running(v1::Simulation::PAUSED, stop_step_ ? "paused after the requested steps" : "paused at the requested time");
  }
}

void Session::stop_running(v1::Simulation::State state, const std::string& reason) {
  {
    std::lock_guard lock(mutex_);
    state_ = state;
    if (state == v1::Simulation::FAILED) failure_reason_ = reason;
  }
  add_event(state == v1::Simulation::FAILED ? "failure" : "state", std::string(state_word(state)) + ": " + reason, "server");
  stop_step_.reset(), stop_time_.reset(), stop_event_.reset();
  publish_status();
  for (auto& waiter : target_waiters_) waiter(here());
  target_waiters_.clear();
  if (state == v1::Simulation::FAILED || state == v1::Simulation::COMPLETED) {
    const grpc::Status never(grpc::StatusCode::FAILED_PRECONDITION,
                             config_.name + " is " + state_word(state) + " before the change's effective time");
    for (auto& change : scheduled_) change.done(here(never));
    scheduled_.clear();
  }
}

// The engine's stage switches (stage_setup.h): to the events, the watch streams and the journal;
// the probes then sample at the new stage's interval, from now.
void Session::report_stage_changes(const std::string& caller) {
  for (const StageChange& c : engine_->take_stage_changes()) {
    const std::string message = (c.from < 0 ? std::string("start: ") : c.from_name + " -> ") + c.to_name + ": " + c.reason;
    add_event("stage_changed", message, caller);
    v1::JournalEntry entry;
    entry.set_caller(caller);
    entry.set_command("stage_changed");
    entry.set_detail(message);
    journal(std::move(entry));
    next_probe_time_ = engine_->time();
  }
}

void Session::sample_outputs(bool force) {
  const double t = engine_->time();
  const double probe_interval = stage_probe_interval(config_.spec, engine_->stage());
  const bool probe_due = t >= next_probe_time_ - 1e-12 * probe_interval;
  const bool energy_due = wall_now() - last_energy_wall_ >= kEnergySampleSeconds;
  if (!force && !probe_due && !energy_due) return;
  // Every process's part of the sample, brought to this one (sample_parts.h): a split engine
  // gathers no frame for it.
  const double mass = config_.engine.water_density * std::pow(config_.engine.dp, config_.engine.dimensions);
  const double ponding = engine_->forcing().ponding_pressure;
  const bool take_probes =
      (probe_due || force) && (probe_samples_.empty() || probe_samples_.back().step() != engine_->step_count());
  const OutputSample taken = combine_sample_parts(
      *probes_, take_probes,
      engine_->parts_at_process_0(
          [&](const FieldFrame& local, const std::vector<char>& owned) {
            return sample_part(*probes_, *cascade_events_, mass, ponding, take_probes, local, owned);
          },
          sample_request(take_probes)));
  kinetic_energy_ = taken.kinetic_energy, max_soil_speed_ = taken.max_soil_speed;
  refresh_pore_water();
  last_energy_wall_ = wall_now();
  // The probes are sampled outside the lock (only this thread writes probe_samples_, so it may
  // read it without one): a case of 10,000 probes held every reader of the session for the
  // sampling (Get of another simulation went from 1 ms to 75 ms).
  std::vector<CascadeEvent> fired;
  if (take_probes) {
    const std::vector<double>& values = taken.probe_values;
    fired = cascade_events_->observe(taken.event_parts, values, ponding);
    if (!probe_names_.empty()) {
      v1::ProbeSample sample;
      sample.set_time(t);
      sample.set_step(engine_->step_count());
      for (double v : values) sample.add_values(v);
      std::lock_guard lock(mutex_);
      probe_samples_.push_back(std::move(sample));
    }
    next_probe_time_ = next_due_time(next_probe_time_, t, probe_interval);
  }
  // The cascade's moments (cascade_events.h): to the event list, the watch streams and the journal.
  for (const CascadeEvent& e : fired) {
    if (stop_event_ && stop_time_ && e.kind == stop_event_->kind()) {  // run_until's earlier end
      stop_time_ = std::min(*stop_time_, t + stop_event_->seconds());
      stop_event_.reset();
    }
    add_event(e.kind, e.message, "solver");
    v1::JournalEntry entry;
    entry.set_caller("solver");
    entry.set_command(e.kind);
    entry.set_detail(e.message);
    journal(std::move(entry));
  }
}

// The engine keeps the account where its particles are (a copy from the device): read with the
// kinetic energy, at a forced sample and at a change of state, not after every step.
void Session::refresh_pore_water() {
  if (engine_ && config_.particles->count(Phase::soil) > 0) pore_water_ = engine_->pore_water_account();
}

void Session::publish_status(bool wait) {
  const double now = wall_now();
  // After a step the status may skip a step rather than make the solver wait for a reader (see
  // run_loop); changes of state wait, so that none is missed.
  std::unique_lock lock(mutex_, std::defer_lock);
  if (wait) {
    lock.lock();
  } else if (!lock.try_lock()) {
    return;
  }
  if (engine_) {
    status_.set_time(engine_->time());
    status_.set_step(engine_->step_count());
    status_.set_dt(engine_->last_dt());
    status_.set_stage(std::uint32_t(engine_->stage()));
    status_.set_stage_name(stage_names_.at(std::size_t(engine_->stage())));
    if (config_.particles->count(Phase::soil) > 0) {  // the pore water's account, for a case with soil
      if (wait) refresh_pore_water();
      v1::PoreWaterAccount& pore_water = *status_.mutable_pore_water();
      pore_water.set_rain(pore_water_.rain);
      pore_water.set_walls(pore_water_.walls);
      pore_water.set_surface(pore_water_.surface);
    }
    if (state_ != v1::Simulation::RUNNING) {
      status_.set_steps_per_second(0);
      rate_wall_ = now, rate_step_ = engine_->step_count();
    } else if (now - rate_wall_ >= kRateSeconds) {
      status_.set_steps_per_second(double(engine_->step_count() - rate_step_) / (now - rate_wall_));
      rate_wall_ = now, rate_step_ = engine_->step_count();
    }
  }
  status_.set_kinetic_energy(kinetic_energy_);
  status_.set_max_soil_speed(max_soil_speed_);
  status_.set_state(state_);
  status_.set_wall_time(now);
}

void Session::add_event(const std::string& kind, const std::string& message, const std::string& caller) {
  v1::Event event;
  event.set_time(engine_ ? engine_->time() : 0.0);
  event.set_step(engine_ ? engine_->step_count() : 0);
  event.set_wall_time(wall_now());
  event.set_kind(kind);
  event.set_message(message);
  event.set_caller(caller);
  std::lock_guard lock(mutex_);
  events_.push_back(std::move(event));
}

void Session::journal(v1::JournalEntry entry) {
  if (!journal_) return;  // the journal itself could not be opened: the set-up has failed
  entry.set_step(engine_ ? engine_->step_count() : 0);
  entry.set_time(engine_ ? engine_->time() : 0.0);
  entry.set_wall_time(wall_now());
  journal_->append(entry);
}

}  // namespace cascade::service
