#include "server/service/simulation_service.h"

#include <algorithm>
#include <cstdio>

#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"
#include "server/service/field_query.h"
#include "server/service/request_validation.h"
#include "server/service/snapshot_request.h"

namespace cascade::service {

namespace {

const std::string kNamePrefix = "simulations/";

grpc::ServerUnaryReactor* finish(grpc::CallbackServerContext* context, const grpc::Status& status) {
  auto* reactor = context->DefaultReactor();
  reactor->Finish(status);
  return reactor;
}

// A stream that ends at once with an error (validation, lookup).
template <typename Message>
class FailedStream : public grpc::ServerWriteReactor<Message> {
 public:
  explicit FailedStream(const grpc::Status& status) { this->Finish(status); }
  void OnDone() override { delete this; }
};

// QueryFields: the frame arrives from the solver thread (Session::query); chunks then go out one
// write at a time, so a slow client holds one chunk, not the frame's worth of messages.
class FieldQueryStream : public grpc::ServerWriteReactor<v1::FieldChunk> {
 public:
  explicit FieldQueryStream(v1::QueryFieldsRequest request) : request_(std::move(request)) {}

  void deliver(const grpc::Status& status, std::shared_ptr<const FieldFrame> frame) {
    if (!status.ok()) return Finish(status);
    const auto selected = FieldQuery::select(request_, std::move(frame), query_);
    if (!selected.ok()) return Finish(selected);
    write_next();
  }
  void OnWriteDone(bool ok) override {
    if (!ok) return Finish(grpc::Status::CANCELLED);
    write_next();
  }
  void OnDone() override { delete this; }

 private:
  void write_next() {
    if (!query_.has_next()) return Finish(grpc::Status::OK);
    chunk_ = query_.next_chunk();
    StartWrite(&chunk_);
  }

  const v1::QueryFieldsRequest request_;
  FieldQuery query_;
  v1::FieldChunk chunk_;
};

}  // namespace

SimulationService::SimulationService(ServiceOptions options) : options_(std::move(options)) {}

SimulationService::~SimulationService() { shutdown(); }

void SimulationService::shutdown() {
  std::map<std::string, std::shared_ptr<Session>> sessions;
  {
    std::lock_guard lock(mutex_);
    shutting_down_ = true;
    sessions.swap(sessions_);
  }
  for (auto& [id, session] : sessions) session->stop("shutdown", "server", /*checkpoint_first=*/true);
  watch_hub_.shutdown();
  snapshot_hub_.shutdown();
}

grpc::Status SimulationService::admit(const grpc::CallbackServerContext& context,
                                      const google::protobuf::Message& request, Role needed, Caller& caller) const {
  if (auto status = options_.access.authorize(context, needed, caller); !status.ok()) return status;
  return check_known_fields(request);
}

grpc::Status SimulationService::lookup(const grpc::CallbackServerContext& context,
                                       const google::protobuf::Message& request, const std::string& name,
                                       Role needed, Caller& caller, std::shared_ptr<Session>& session) const {
  if (auto status = admit(context, request, needed, caller); !status.ok()) return status;
  std::string id;
  if (auto status = check_simulation_name("name", name, id); !status.ok()) return status;
  std::lock_guard lock(mutex_);
  if (shutting_down_) return {grpc::StatusCode::UNAVAILABLE, "the server is shutting down"};
  const auto found = sessions_.find(id);
  if (found == sessions_.end()) return {grpc::StatusCode::NOT_FOUND, "name: no simulation " + name};
  session = found->second;
  return grpc::Status::OK;
}

std::string SimulationService::new_id() const {
  for (unsigned n = unsigned(sessions_.size()) + 1;; ++n) {
    char id[16];
    std::snprintf(id, sizeof id, "sim-%04u", n);
    if (!sessions_.count(id) && !std::filesystem::exists(options_.data_dir / "simulations" / id)) return id;
  }
}

SessionConfig SimulationService::session_config(const std::string& id, v1::ScenarioSpec spec,
                                              const std::string& caller) const {
  SessionConfig session;
  session.name = kNamePrefix + id;
  session.particles = std::make_shared<const HostParticles>(build_particle_set(spec).particles);
  session.engine = engine_config(spec, *session.particles, options_.precision, options_.device);
  session.spec = std::move(spec);
  session.make_engine = options_.make_engine ? options_.make_engine : EngineFactory(&cascade::make_engine);
  if (options_.split_engine) session.make_engine = options_.split_engine(session.spec);
  session.directory = options_.data_dir / "simulations" / id;
  session.threads = options_.threads;
  session.caller = caller;
  return session;
}

grpc::Status SimulationService::create(const grpc::CallbackServerContext& context,
                                       const v1::CreateSimulationRequest& request, v1::Simulation& response) {
  Caller caller;
  if (auto status = admit(context, request, Role::operator_, caller); !status.ok()) return status;
  if (!request.simulation_id().empty())
    if (auto status = check_simulation_id("simulation_id", request.simulation_id()); !status.ok()) return status;

  v1::ScenarioSpec spec;
  try {
    if (request.has_case_yaml()) {
      if (request.case_yaml().size() > kMaxCaseYamlBytes)
        return {grpc::StatusCode::RESOURCE_EXHAUSTED, "case_yaml: more than 1 MiB of text"};
      std::vector<CaseOverride> overrides;
      for (int k = 0; k < request.overrides_size(); ++k) {
        try {
          overrides.push_back(parse_override(request.overrides(k)));
        } catch (const CaseError& e) {
          return invalid("overrides[" + std::to_string(k) + "]", e.what());
        }
      }
      spec = load_case_text(request.case_yaml(), overrides, "case_yaml");
    } else if (request.has_spec()) {
      if (request.overrides_size() > 0) return invalid("overrides", "apply to case_yaml only");
      spec = request.spec();
      validate_spec(spec);
      apply_defaults(spec);
    } else {
      return invalid("scenario", "give case_yaml or spec");
    }
  } catch (const CaseError& e) {
    return invalid(request.has_spec() ? "spec" : "case_yaml", e.what());
  }
  SessionConfig session;
  try {
    session = session_config(request.simulation_id(), std::move(spec), caller.name);
  } catch (const CaseError& e) {
    return invalid(request.has_spec() ? "spec" : "case_yaml", e.what());
  }
  if (session.particles->size() > options_.max_particles)
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "particles: the case has " + std::to_string(session.particles->size()) + ", the server takes at most " +
                std::to_string(options_.max_particles) + " (--max-particles)"};

  std::lock_guard lock(mutex_);
  if (shutting_down_) return {grpc::StatusCode::UNAVAILABLE, "the server is shutting down"};
  if (sessions_.size() >= options_.max_simulations)
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "simulations: the server holds " + std::to_string(sessions_.size()) + ", its limit (--max-simulations); delete one first"};
  const std::string id = request.simulation_id().empty() ? new_id() : request.simulation_id();
  const auto directory = options_.data_dir / "simulations" / id;
  if (sessions_.count(id) || std::filesystem::exists(directory))
    return {grpc::StatusCode::ALREADY_EXISTS, "simulation_id: simulations/" + id + " exists"};
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) return {grpc::StatusCode::INTERNAL, "cannot create " + directory.string() + ": " + error.message()};

  session.name = kNamePrefix + id;
  session.directory = directory;
  auto created = std::make_shared<Session>(std::move(session));
  response = created->describe();
  sessions_.emplace(id, std::move(created));
  return grpc::Status::OK;
}

grpc::ServerUnaryReactor* SimulationService::CreateSimulation(grpc::CallbackServerContext* context,
                                                              const v1::CreateSimulationRequest* request,
                                                              v1::Simulation* response) {
  // A defect of the loader or builder (not of the case) answers INTERNAL with its text: uncaught,
  // gRPC answered an empty UNIMPLEMENTED, which reads as a request that did not parse.
  grpc::Status status;
  try {
    status = create(*context, *request, *response);
  } catch (const std::exception& e) {
    status = {grpc::StatusCode::INTERNAL, std::string("internal error while creating the simulation: ") + e.what()};
  }
  return finish(context, status);
}

grpc::ServerUnaryReactor* SimulationService::GetSimulation(grpc::CallbackServerContext* context,
                                                           const v1::GetSimulationRequest* request,
                                                           v1::Simulation* response) {
  Caller caller;
  std::shared_ptr<Session> session;
  auto status = lookup(*context, *request, request->name(), Role::viewer, caller, session);
  if (status.ok()) *response = session->describe();
  return finish(context, status);
}

grpc::ServerUnaryReactor* SimulationService::ListSimulations(grpc::CallbackServerContext* context,
                                                             const v1::ListSimulationsRequest* request,
                                                             v1::ListSimulationsResponse* response) {
  Caller caller;
  if (auto status = admit(*context, *request, Role::viewer, caller); !status.ok())
    return finish(context, status);
  std::lock_guard lock(mutex_);
  for (const auto& [id, session] : sessions_) *response->add_simulations() = session->describe();
  return finish(context, grpc::Status::OK);
}

grpc::ServerUnaryReactor* SimulationService::DeleteSimulation(grpc::CallbackServerContext* context,
                                                              const v1::DeleteSimulationRequest* request,
                                                              google::protobuf::Empty*) {
  Caller caller;
  std::shared_ptr<Session> session;
  if (auto status = lookup(*context, *request, request->name(), Role::operator_, caller, session); !status.ok())
    return finish(context, status);
  {
    std::lock_guard lock(mutex_);
    sessions_.erase(request->name().substr(kNamePrefix.size()));
  }
  // Waits for the solver's current step at most; the journal then ends with `delete`.
  session->stop("delete", caller.name);
  return finish(context, grpc::Status::OK);
}

template <typename Command>
grpc::ServerUnaryReactor* SimulationService::control(grpc::CallbackServerContext* context,
                                                     const google::protobuf::Message& request, const std::string& name,
                                                     v1::Simulation* response, Command command) {
  Caller caller;
  std::shared_ptr<Session> session;
  if (auto status = lookup(*context, request, name, Role::operator_, caller, session); !status.ok())
    return finish(context, status);
  auto* reactor = context->DefaultReactor();
  // The session outlives its solver thread's callbacks (stop() joins it), so a plain pointer does.
  Session* raw = session.get();
  command(*session, caller.name, [reactor, response, raw](const Session::Outcome& outcome) {
    if (outcome.status.ok()) *response = raw->describe();
    reactor->Finish(outcome.status);
  });
  return reactor;
}

grpc::ServerUnaryReactor* SimulationService::StartSimulation(grpc::CallbackServerContext* context,
                                                             const v1::StartSimulationRequest* request,
                                                             v1::Simulation* response) {
  return control(context, *request, request->name(), response,
                 [](Session& s, const std::string& caller, Session::Done done) { s.start(caller, std::move(done)); });
}

grpc::ServerUnaryReactor* SimulationService::PauseSimulation(grpc::CallbackServerContext* context,
                                                             const v1::PauseSimulationRequest* request,
                                                             v1::Simulation* response) {
  return control(context, *request, request->name(), response,
                 [](Session& s, const std::string& caller, Session::Done done) { s.pause(caller, std::move(done)); });
}

grpc::ServerUnaryReactor* SimulationService::ResumeSimulation(grpc::CallbackServerContext* context,
                                                              const v1::ResumeSimulationRequest* request,
                                                              v1::Simulation* response) {
  return control(context, *request, request->name(), response,
                 [](Session& s, const std::string& caller, Session::Done done) { s.resume(caller, std::move(done)); });
}

grpc::ServerUnaryReactor* SimulationService::StepSimulation(grpc::CallbackServerContext* context,
                                                            const v1::StepSimulationRequest* request,
                                                            v1::Simulation* response) {
  if (auto status = check_step(*request); !status.ok()) return finish(context, status);
  const std::uint64_t steps = request->steps();
  return control(context, *request, request->name(), response, [steps](Session& s, const std::string& caller, Session::Done done) {
    s.step(steps, caller, std::move(done));
  });
}

grpc::ServerUnaryReactor* SimulationService::RunSimulationUntil(grpc::CallbackServerContext* context,
                                                                const v1::RunSimulationUntilRequest* request,
                                                                v1::Simulation* response) {
  const v1::RunSimulationUntilRequest checked = *request;
  return control(context, *request, request->name(), response,
                 [checked](Session& s, const std::string& caller, Session::Done done) {
                   if (auto status = check_run_until(checked, s.spec().end_time()); !status.ok())
                     return done({status, 0, 0});
                   s.run_until(checked.time(), caller, std::move(done),
                               checked.has_stop_after_event() ? std::optional(checked.stop_after_event()) : std::nullopt);
                 });
}

grpc::ServerUnaryReactor* SimulationService::UpdateForcing(grpc::CallbackServerContext* context,
                                                           const v1::UpdateForcingRequest* request,
                                                           v1::UpdateForcingResponse* response) {
  Caller caller;
  std::shared_ptr<Session> session;
  if (auto status = lookup(*context, *request, request->name(), Role::operator_, caller, session); !status.ok())
    return finish(context, status);
  const auto current = session->describe().forcing();
  if (auto status = check_update_forcing(*request, current, session->spec().dimensions(), session->spec().end_time());
      !status.ok())
    return finish(context, status);
  auto* reactor = context->DefaultReactor();
  Session* raw = session.get();
  std::optional<double> effective_time;
  if (request->has_effective_time()) effective_time = request->effective_time();
  session->update_forcing(request->forcing(), {request->update_mask().paths().begin(), request->update_mask().paths().end()},
                          effective_time, caller.name, [reactor, response, raw](const Session::Outcome& outcome) {
                            if (outcome.status.ok()) {
                              response->set_effective_step(outcome.step + 1);
                              response->set_effective_time(outcome.time);
                              *response->mutable_forcing() = raw->describe().forcing();
                            }
                            reactor->Finish(outcome.status);
                          });
  return reactor;
}

grpc::ServerUnaryReactor* SimulationService::AdvanceStage(grpc::CallbackServerContext* context,
                                                          const v1::AdvanceStageRequest* request,
                                                          v1::Simulation* response) {
  const v1::AdvanceStageRequest checked = *request;
  return control(context, *request, request->name(), response,
                 [checked](Session& s, const std::string& caller, Session::Done done) {
                   if (auto status = check_advance_stage(checked); !status.ok()) return done({status, 0, 0});
                   s.advance_stage(checked.reason(), caller, std::move(done));
                 });
}

grpc::ServerWriteReactor<v1::FieldChunk>* SimulationService::QueryFields(grpc::CallbackServerContext* context,
                                                                         const v1::QueryFieldsRequest* request) {
  Caller caller;
  std::shared_ptr<Session> session;
  auto status = lookup(*context, *request, request->name(), Role::viewer, caller, session);
  if (status.ok()) status = check_query(*request);
  if (!status.ok()) return new FailedStream<v1::FieldChunk>(status);
  auto* stream = new FieldQueryStream(*request);
  session->query([stream](const grpc::Status& s, std::shared_ptr<const FieldFrame> frame) {
    stream->deliver(s, std::move(frame));
  });
  return stream;
}

grpc::ServerUnaryReactor* SimulationService::ListProbes(grpc::CallbackServerContext* context,
                                                        const v1::ListProbesRequest* request,
                                                        v1::ListProbesResponse* response) {
  Caller caller;
  std::shared_ptr<Session> session;
  auto status = lookup(*context, *request, request->name(), Role::viewer, caller, session);
  if (status.ok()) status = check_since_time(request->since_time());
  if (status.ok()) {
    for (const auto& name : session->probe_names()) response->add_probe_names(name);
    for (auto& sample : session->probe_samples(request->since_time())) *response->add_samples() = std::move(sample);
  }
  return finish(context, status);
}

grpc::ServerUnaryReactor* SimulationService::ListEvents(grpc::CallbackServerContext* context,
                                                        const v1::ListEventsRequest* request,
                                                        v1::ListEventsResponse* response) {
  Caller caller;
  std::shared_ptr<Session> session;
  auto status = lookup(*context, *request, request->name(), Role::viewer, caller, session);
  if (status.ok()) status = check_since_time(request->since_time());
  if (status.ok())
    for (auto& event : session->events())
      if (event.time() >= request->since_time()) *response->add_events() = std::move(event);
  return finish(context, status);
}

grpc::ServerWriteReactor<v1::WatchSimulationResponse>* SimulationService::WatchSimulation(
    grpc::CallbackServerContext* context, const v1::WatchSimulationRequest* request) {
  Caller caller;
  std::shared_ptr<Session> session;
  auto status = lookup(*context, *request, request->name(), Role::viewer, caller, session);
  if (status.ok()) status = check_watch(*request);
  if (!status.ok()) return new FailedStream<v1::WatchSimulationResponse>(status);
  const double interval = request->interval_seconds() > 0 ? request->interval_seconds() : 1.0;
  return watch_hub_.watch(std::move(session), interval);
}


grpc::ServerUnaryReactor* SimulationService::RenderSnapshot(grpc::CallbackServerContext* context,
                                                            const v1::RenderSnapshotRequest* request,
                                                            v1::SnapshotImage* response) {
  Caller caller;
  std::shared_ptr<Session> session;
  render::SnapshotSettings settings;
  auto status = lookup(*context, *request, request->name(), Role::viewer, caller, session);
  if (status.ok()) status = snapshot_settings_for(session->spec(), request->snapshot(), settings);
  if (!status.ok()) return finish(context, status);
  auto* reactor = context->DefaultReactor();
  // The solver thread copies the frame at its next step boundary; the render thread draws it.
  session->query([this, reactor, response, settings](const grpc::Status& s, std::shared_ptr<const FieldFrame> frame) {
    if (!s.ok()) return reactor->Finish(s);
    snapshot_hub_.render(std::move(frame), settings, [reactor, response](const grpc::Status& r, v1::SnapshotImage image) {
      if (r.ok()) *response = std::move(image);
      reactor->Finish(r);
    });
  });
  return reactor;
}

grpc::ServerWriteReactor<v1::SnapshotImage>* SimulationService::StreamSnapshots(
    grpc::CallbackServerContext* context, const v1::StreamSnapshotsRequest* request) {
  Caller caller;
  std::shared_ptr<Session> session;
  render::SnapshotSettings settings;
  auto status = lookup(*context, *request, request->name(), Role::viewer, caller, session);
  if (status.ok()) status = snapshot_settings_for(session->spec(), request->snapshot(), settings);
  if (status.ok()) status = check_snapshot_interval(*request);
  if (!status.ok()) return new FailedStream<v1::SnapshotImage>(status);
  const bool simulated = request->has_every_simulated_seconds();
  const SnapshotInterval interval{simulated, simulated ? request->every_simulated_seconds() : request->every_wall_seconds()};
  return snapshot_hub_.stream(std::move(session), std::move(settings), interval);
}

}  // namespace cascade::service
