// One simulation on the server: its Engine on a solver thread of its own, the command queue that
// is the only way in, and what clients read (status, events, probe samples) published under a
// mutex at step boundaries.
//
// RPC handlers never touch the engine: every method here queues a command and returns. The solver
// thread applies the queued commands at the next step boundary, appends each applied one to the
// journal (flushed to disk) and only then calls the command's `done`. Readers copy the published
// state; they never wait for a step, and the solver never waits for them.
#pragma once

#include <grpcpp/support/status.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cascade/v1/simulation.pb.h"
#include "server/core/engine.h"
#include "server/io/checkpoint_file.h"
#include "server/io/journal.h"
#include "server/io/probe_sampler.h"
#include "server/scenario/cascade_events.h"
#include "server/scenario/rain_series.h"
#include "server/service/frame_tap.h"

namespace cascade::service {

using EngineFactory = std::function<std::unique_ptr<Engine>(const EngineConfig&, const HostParticles&)>;

// What a fork takes from its parent besides the checkpoint: the run so far as clients saw it, so
// that the fork's events and probes go on from the parent's, and no cascade event fires twice.
struct ForkHistory {
  std::vector<v1::Event> events;
  std::vector<v1::ProbeSample> probe_samples;
  CascadeEventDetector cascade_events;
  double next_probe_time = 0;
  double kinetic_energy = 0, max_soil_speed = 0;  // as last sampled
  PoreWaterAccount pore_water;
  v1::Forcing forcing;  // as published, with the rain's factor
  CaseRain rain;        // the steering of the case's rain so far
};

// A checkpoint to start from instead of the case's initial state: RestoreCheckpoint's file, or a
// fork of a running session (ForkSimulation: `engine` is the parent's clone, `checkpoint` has the
// journal but no engine state, `fork` the history).
struct RestoreSource {
  std::string checkpoint_name;  // simulations/{id}/checkpoints/{checkpoint_id}; a fork: its parent at step N
  Checkpoint checkpoint;
  std::unique_ptr<Engine> engine;
  std::optional<ForkHistory> fork;
};

struct SessionConfig {
  std::string name;                  // simulations/{id}
  v1::ScenarioSpec spec;             // defaults applied
  // The initial state; a fork shares its parent's (the engine's state is what it copies).
  std::shared_ptr<const HostParticles> particles;
  EngineConfig engine;               // from engine_config(spec, particles, ...)
  EngineFactory make_engine;         // run on the solver thread
  std::filesystem::path directory;   // holds journal.jsonl
  int threads = 0;                   // OpenMP threads of the solver thread; 0: its share of the free cores
  std::string caller;                // who created it (journal)
  // Set: the engine takes the checkpoint's state (no initialisation stage), journal.jsonl becomes
  // the checkpoint's journal (the one it replaces is kept as journal.jsonl.replaced-N) and the
  // simulation is PAUSED there.
  std::shared_ptr<RestoreSource> restore;
};

class Session {
 public:
  // When a command has been applied (and journaled), or refused: the step count and simulated time
  // at that step boundary. A step or run-until command is done when its target is reached or the
  // run stops before it.
  struct Outcome {
    grpc::Status status;
    std::uint64_t step = 0;
    double time = 0;
  };
  using Done = std::function<void(const Outcome&)>;
  // A query's frame, copied at a step boundary (null with a failed status).
  using FrameDone = std::function<void(const grpc::Status&, std::shared_ptr<const FieldFrame>)>;
  // A checkpoint written at a step boundary: its file (empty with a failed status).
  using CheckpointDone = std::function<void(const grpc::Status&, const std::filesystem::path&)>;
  // A fork's source taken at a step boundary (null with a failed status): the state, the journal
  // up to and with the parent's `fork` entry, and the history clients saw.
  using ForkDone = std::function<void(const grpc::Status&, std::shared_ptr<RestoreSource>)>;

  // Starts the solver thread, which builds the engine and runs the case's initialisation stage.
  explicit Session(SessionConfig config);
  // Stops the solver thread (stop()).
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  void start(const std::string& caller, Done done);
  void pause(const std::string& caller, Done done);
  void resume(const std::string& caller, Done done);
  void step(std::uint64_t steps, const std::string& caller, Done done);
  // With `stop`, the run ends earlier: stop.seconds after the first cascade event of stop.kind.
  void run_until(double time, const std::string& caller, Done done, std::optional<v1::EventStop> stop = std::nullopt);
  // `mask` holds validated paths of kSteerableForcingFields; without `effective_time` the change
  // applies at the next step boundary, else at the first one at or after that time.
  void update_forcing(const v1::Forcing& forcing, std::vector<std::string> mask, std::optional<double> effective_time,
                      const std::string& caller, Done done);
  // The hand-over to the case's next stage (Engine::advance_stage) at the next step boundary;
  // `reason` goes to the journal. FAILED_PRECONDITION when COMPLETED, FAILED or at the last stage.
  void advance_stage(const std::string& reason, const std::string& caller, Done done);
  void query(FrameDone done);
  // From the next step boundary on, offers `tap` every frame (the first at once); forgotten when
  // the tap is destroyed.
  void tap_frames(std::weak_ptr<FrameTap> tap);
  // Writes a checkpoint (checkpoint_store.h) at the next step boundary; a running simulation goes
  // on after it. FAILED_PRECONDITION for a FAILED simulation, whose state holds the failure.
  void checkpoint(const std::string& caller, CheckpointDone done);
  // Takes a fork's source at the next step boundary and journals `fork` with the fork's name; a
  // running simulation goes on after it. FAILED_PRECONDITION for a FAILED simulation.
  void fork(const std::string& fork_name, const std::string& caller, ForkDone done);

  // Ends the solver thread at the next step boundary (a running simulation pauses there), writes
  // `reason` (shutdown, delete, restore) to the journal and refuses what is still queued; with
  // `checkpoint_first`, a RUNNING or PAUSED simulation writes a checkpoint before. Idempotent.
  void stop(const std::string& reason, const std::string& caller, bool checkpoint_first = false);

  const std::string& name() const { return config_.name; }
  const v1::ScenarioSpec& spec() const { return config_.spec; }
  std::size_t particle_count() const { return config_.particles->size(); }
  const SessionConfig& config() const { return config_; }

  v1::Simulation describe() const;
  v1::Status status() const;
  bool stopped() const;  // COMPLETED, FAILED, or the solver thread has ended
  std::vector<std::string> probe_names() const { return probe_names_; }
  std::vector<v1::ProbeSample> probe_samples(double since_time) const;
  // The events from index `first` on (events are only ever appended).
  std::vector<v1::Event> events(std::size_t first = 0) const;

 private:
  struct Command;
  struct ScheduledForcing;

  void enqueue(Command command);
  void run_loop();
  void initialise();
  void restore();  // initialise() from restore_source_
  std::filesystem::path take_checkpoint(const std::string& caller);
  std::shared_ptr<RestoreSource> take_fork(const std::string& fork_name, const std::string& caller);
  void apply(Command& command);
  void apply_forcing_change(const ScheduledForcing& change);
  v1::Forcing forcing_now() const;  // the engine's forcing with the rain's factor
  void advance();  // one step while running, with everything that follows it
  void reach_targets();
  void stop_running(v1::Simulation::State state, const std::string& reason);
  void report_stage_changes(const std::string& caller);  // `caller`: who made them (the solver, an operator)
  void sample_outputs(bool force);
  void publish_status(bool wait = true);
  void refresh_pore_water();
  void feed_taps();
  void add_event(const std::string& kind, const std::string& message, const std::string& caller);
  void journal(v1::JournalEntry entry);
  bool refused_when_ended(const Done& done, const char* what);
  bool transition(const Done& done, std::initializer_list<v1::Simulation::State> from, const char* command);
  Outcome here(grpc::Status status = grpc::Status::OK) const;

  // SessionConfig::restore, taken out of the config and dropped once the engine has its state:
  // the checkpoint's arrays would otherwise stay as a second copy of the state for the session's
  // life. Declared before config_, which is built after it.
  std::shared_ptr<RestoreSource> restore_source_;
  const SessionConfig config_;
  const std::vector<std::string> probe_names_;
  const std::vector<std::string> stage_names_;  // by index; one "dynamic" for a case without stages

  // Shared with the RPC threads, under mutex_.
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Command> queue_;
  std::atomic<bool> stop_requested_{false};  // also read without the lock by the solver thread
  std::string stop_reason_, stop_caller_;
  bool checkpoint_on_stop_ = false;
  bool thread_ended_ = false;
  v1::Simulation::State state_ = v1::Simulation::CREATED;
  std::string failure_reason_;
  v1::Status status_;
  v1::Forcing forcing_;
  std::vector<v1::Event> events_;
  std::vector<v1::ProbeSample> probe_samples_;

  // The solver thread's own.
  std::unique_ptr<Engine> engine_;
  std::unique_ptr<JournalWriter> journal_;
  std::unique_ptr<ProbeSampler> probes_;
  std::unique_ptr<CascadeEventDetector> cascade_events_;  // ponding, onset, impact, waves, overtopping
  std::vector<ScheduledForcing> scheduled_;
  std::optional<std::uint64_t> stop_step_;
  std::optional<double> stop_time_;
  std::optional<v1::EventStop> stop_event_;  // run_until's: stop_time_ moves to its event's time + seconds
  std::vector<Done> target_waiters_;
  std::vector<std::weak_ptr<FrameTap>> frame_taps_;
  CaseRain rain_;  // the case's rain and the operator's steering of it
  double next_probe_time_ = 0;
  double last_energy_wall_ = 0;
  double rate_wall_ = 0;
  std::uint64_t rate_step_ = 0;
  std::size_t lost_particles_ = 0;
  double kinetic_energy_ = 0, max_soil_speed_ = 0;
  PoreWaterAccount pore_water_;  // as of the last sample (refresh_pore_water)

  std::mutex join_mutex_;  // stop() may come from the delete handler and from shutdown at once
  std::thread thread_;
};

}  // namespace cascade::service
