#include "server/parallel/split_server.h"

#include <mpi.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "server/io/probe_sampler.h"
#include "server/io/sample_parts.h"
#include "server/parallel/distributed_engine.h"
#include "server/parallel/mpi_transport.h"
#include "server/parallel/state_message.h"
#include "server/scenario/cascade_events.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"

namespace cascade {
namespace {

// What process 0 announces on MPI_COMM_WORLD: a new engine (the case follows), or the end.
enum class Announcement : std::uint32_t { engine = 1, finish = 2 };

// What process 0's engine hands to the others on the engine's communicator.
enum class Call : std::uint32_t {
  step = 1,
  set_forcing,
  frame,
  lost_particles,
  device_bytes,
  pore_water_account,
  state,
  restore,
  zero_velocities,
  set_relaxation,
  restart_clock,
  equilibrium,
  refresh_seepage,
  sample_parts,
  end,
};

void check(int result, const char* what) {
  if (result != MPI_SUCCESS) throw std::runtime_error(std::string(what) + " failed");
}

// Waits for `request` without holding a core: MPI's blocking calls poll, and a process waits for
// process 0's next call as long as a simulation is paused (and for the next announcement as long
// as the server runs). A call that follows at once (the next step) is met within microseconds.
void wait_idle(MPI_Request& request) {
  for (int polls = 0;; ++polls) {
    int done = 0;
    check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
    if (done) return;
    if (polls < 1000) std::this_thread::yield();
    else std::this_thread::sleep_for(std::chrono::microseconds(polls < 2000 ? 50 : 1000));
  }
}

// Nonblocking on every process (a nonblocking collective matches only nonblocking ones).
void broadcast_part(void* data, int count, MPI_Datatype type, MPI_Comm communicator) {
  int process = 0;
  MPI_Comm_rank(communicator, &process);
  MPI_Request request;
  check(MPI_Ibcast(data, count, type, 0, communicator, &request), "MPI_Ibcast");
  if (process == 0) check(MPI_Wait(&request, MPI_STATUS_IGNORE), "MPI_Wait");
  else wait_idle(request);
}

// A kind and its bytes from process 0 (root of `communicator`) to all.
void broadcast(MPI_Comm communicator, std::uint32_t& kind, std::vector<char>& bytes) {
  std::uint64_t header[2] = {kind, bytes.size()};
  broadcast_part(header, 2, MPI_UINT64_T, communicator);
  kind = std::uint32_t(header[0]);
  bytes.resize(std::size_t(header[1]));
  std::size_t at = 0;
  while (at < bytes.size()) {  // MPI's counts are ints
    const int chunk = int(std::min<std::size_t>(bytes.size() - at, 1u << 30));
    broadcast_part(bytes.data() + at, chunk, MPI_BYTE, communicator);
    at += std::size_t(chunk);
  }
}

// Process 0's engine: its share of the run, and the others told of every call they must make too.
class LeaderEngine final : public Engine {
 public:
  // `sibling` makes another engine of the same case, split the same way (a fork's).
  LeaderEngine(const EngineConfig& config, const HostParticles& whole, MPI_Comm communicator,
               std::function<std::unique_ptr<Engine>()> sibling)
      : communicator_(communicator), transport_(communicator), sibling_(std::move(sibling)) {
    try {
      engine_ = std::make_unique<DistributedEngine>(config, whole, transport_);
    } catch (...) {  // the others met the same (the same case, the same rule) and freed theirs
      MPI_Comm_free(&communicator_);
      throw;
    }
  }
  ~LeaderEngine() override {
    try {
      call(Call::end);
    } catch (...) {
    }
    engine_.reset();
    MPI_Comm_free(&communicator_);
  }

  void step() override { call(Call::step), engine_->step(); }
  double time() const override { return engine_->time(); }
  std::uint64_t step_count() const override { return engine_->step_count(); }
  double last_dt() const override { return engine_->last_dt(); }
  std::size_t particle_count() const override { return engine_->particle_count(); }
  std::size_t lost_particles() const override { return call(Call::lost_particles), engine_->lost_particles(); }
  std::size_t device_bytes() const override { return call(Call::device_bytes), engine_->device_bytes(); }
  FieldFrame frame() const override { return call(Call::frame), engine_->frame_at_process_0(); }
  const char* device_name() const override { return engine_->device_name(); }
  void set_forcing(const HydraulicForcing& forcing) override {
    std::vector<char> bytes(sizeof forcing);
    std::memcpy(bytes.data(), &forcing, sizeof forcing);
    call(Call::set_forcing, bytes);
    engine_->set_forcing(forcing);
  }
  HydraulicForcing forcing() const override { return engine_->forcing(); }
  void restart_clock() override { call(Call::restart_clock), engine_->restart_clock(); }
  EngineState state() const override { return call(Call::state), engine_->state_at_process_0(); }
  void restore(const EngineState& state) override { call(Call::restore, state_message(state)), engine_->restore(state); }
  // A fork: a sibling engine that restores this one's state (to round-off what this one would
  // do: its shares are cut anew).
  std::unique_ptr<Engine> clone() const override {
    const EngineState now = state();
    std::unique_ptr<Engine> copy = sibling_();
    copy->restore(now);
    return copy;
  }
  PoreWaterAccount pore_water_account() const override {
    return call(Call::pore_water_account), engine_->pore_water_account();
  }
  void set_relaxation(double local_damping) override {
    std::vector<char> bytes(sizeof local_damping);
    std::memcpy(bytes.data(), &local_damping, sizeof local_damping);
    call(Call::set_relaxation, bytes), engine_->set_relaxation(local_damping);
  }
  Equilibrium equilibrium() const override { return call(Call::equilibrium), engine_->equilibrium(); }
  void refresh_seepage() override { call(Call::refresh_seepage), engine_->refresh_seepage(); }
  void zero_velocities() override { call(Call::zero_velocities), engine_->zero_velocities(); }
  // The others take their parts with a sampler and detector of their own of the same case
  // (follow_engine), as `request` asks (sample_request: the probes and events, or the energy alone).
  std::vector<std::vector<char>> parts_at_process_0(const SamplePart& part,
                                                    const std::vector<char>& request) const override {
    call(Call::sample_parts, request);
    return engine_->parts_at_process_0(part, request);
  }
  LoadBalance load_balance() const override { return engine_->load_balance(); }

 private:
  void call(Call c, std::vector<char> bytes = {}) const {
    auto kind = std::uint32_t(c);
    broadcast(communicator_, kind, bytes);
  }

  MPI_Comm communicator_;
  MpiTransport transport_;
  std::function<std::unique_ptr<Engine>()> sibling_;
  std::unique_ptr<DistributedEngine> engine_;
};

// Another process's share of one engine: the calls of process 0's LeaderEngine, made on it, until
// the engine ends. A failure is met by every process at the same reduction (DistributedEngine),
// and process 0 reports it; here the share waits for the next call.
void follow_engine(const std::string& case_bytes, Precision precision, Device device, int threads, MPI_Comm communicator) {
  if (threads > 0) omp_set_num_threads(threads);
  v1::ScenarioSpec spec;
  spec.ParseFromString(case_bytes);
  std::unique_ptr<DistributedEngine> engine;
  MpiTransport transport(communicator);
  std::unique_ptr<ProbeSampler> probes;
  std::unique_ptr<CascadeEventDetector> events;
  double mass = 0;
  try {
    const HostParticles particles = build_particle_set(spec).particles;
    const EngineConfig config = engine_config(spec, particles, precision, device);
    engine = std::make_unique<DistributedEngine>(config, particles, transport);
    mass = config.water_density * std::pow(config.dp, config.dimensions);  // as the session's (session.cpp)
    probes = std::make_unique<ProbeSampler>(spec, config.h, mass);
    events = std::make_unique<CascadeEventDetector>(spec, config.h, probes->names());
  } catch (const std::exception&) {  // process 0 met the same and reports it
    MPI_Comm_free(&communicator);
    return;
  }
  for (;;) {
    std::uint32_t kind = 0;
    std::vector<char> bytes;
    broadcast(communicator, kind, bytes);
    const Call c = Call(kind);
    if (c == Call::end) break;
    try {
      switch (c) {
        case Call::step: engine->step(); break;
        case Call::set_forcing: {
          HydraulicForcing forcing;
          if (bytes.size() != sizeof forcing) throw std::logic_error("a forcing message of the wrong size");
          std::memcpy(&forcing, bytes.data(), sizeof forcing);
          engine->set_forcing(forcing);
          break;
        }
        case Call::frame: engine->frame_at_process_0(); break;
        case Call::lost_particles: engine->lost_particles(); break;
        case Call::device_bytes: engine->device_bytes(); break;
        case Call::pore_water_account: engine->pore_water_account(); break;
        case Call::state: engine->state_at_process_0(); break;
        case Call::restore: engine->restore(state_from_message(bytes)); break;
        case Call::zero_velocities: engine->zero_velocities(); break;
        case Call::set_relaxation: {
          double local_damping = 0;
          if (bytes.size() != sizeof local_damping) throw std::logic_error("a damping message of the wrong size");
          std::memcpy(&local_damping, bytes.data(), sizeof local_damping);
          engine->set_relaxation(local_damping);
          break;
        }
        case Call::restart_clock: engine->restart_clock(); break;
        case Call::equilibrium: engine->equilibrium(); break;
        case Call::refresh_seepage: engine->refresh_seepage(); break;
        case Call::sample_parts: {
          // The request is read inside the part: a malformed one is this process's failed part,
          // which process 0 reports, not a failure here that would leave it waiting.
          const Engine::SamplePart part = [&](const FieldFrame& local, const std::vector<char>& owned) {
            return sample_part(*probes, *events, mass, engine->forcing().ponding_pressure,
                               sample_request_with_probes(bytes), local, owned);
          };
          engine->parts_at_process_0(part, bytes);
          break;
        }
        case Call::end: break;
      }
    } catch (const std::exception& e) {
      // Met by every process at one of the call's reductions, process 0 reports it too; met here
      // alone, process 0 waits in the call's next exchange, and this line is what tells why.
      int process = 0;
      MPI_Comm_rank(communicator, &process);
      std::fprintf(stderr, "cascade-server: process %d: %s\n", process, e.what());
    }
  }
  engine.reset();
  MPI_Comm_free(&communicator);
}

}  // namespace

SplitEngineFactory SplitEngineLauncher::factory(const v1::ScenarioSpec& spec) {
  std::string case_bytes;
  spec.SerializeToString(&case_bytes);
  return [this, case_bytes](const EngineConfig& config, const HostParticles& whole) {
    return launch(case_bytes, config, std::make_shared<const HostParticles>(whole));
  };
}

std::unique_ptr<Engine> SplitEngineLauncher::launch(const std::string& case_bytes, const EngineConfig& config,
                                                    std::shared_ptr<const HostParticles> whole) {
  MPI_Comm communicator = MPI_COMM_NULL;
  {
    std::lock_guard lock(world_);
    auto kind = std::uint32_t(Announcement::engine);
    std::vector<char> bytes(case_bytes.begin(), case_bytes.end());
    broadcast(MPI_COMM_WORLD, kind, bytes);
    check(MPI_Comm_dup(MPI_COMM_WORLD, &communicator), "MPI_Comm_dup");
  }
  return std::make_unique<LeaderEngine>(config, *whole, communicator,
                                        [this, case_bytes, config, whole] { return launch(case_bytes, config, whole); });
}

void SplitEngineLauncher::finish() {
  std::lock_guard lock(world_);
  auto kind = std::uint32_t(Announcement::finish);
  std::vector<char> none;
  broadcast(MPI_COMM_WORLD, kind, none);
}

void follow_split_engines(Precision precision, Device device, int threads) {
  std::vector<std::thread> engines;
  for (;;) {
    std::uint32_t kind = 0;
    std::vector<char> bytes;
    broadcast(MPI_COMM_WORLD, kind, bytes);
    if (Announcement(kind) != Announcement::engine) break;
    MPI_Comm communicator = MPI_COMM_NULL;
    check(MPI_Comm_dup(MPI_COMM_WORLD, &communicator), "MPI_Comm_dup");
    engines.emplace_back(follow_engine, std::string(bytes.begin(), bytes.end()), precision, device, threads,
                         communicator);
  }
  for (auto& engine : engines) engine.join();
}

}  // namespace cascade
