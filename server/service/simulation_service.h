// cascade.v1.SimulationService on the gRPC callback API: the registry of Sessions, access
// control, request validation, and the streams. Handlers only validate, look up and queue: the
// replies of commands come from the solver threads once applied (session.h).
//
// Tests register it with a grpc::ServerBuilder and talk to it through the server's in-process
// channel or over loopback, as cascade-server does (server/app).
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "cascade/v1/simulation.grpc.pb.h"
#include "server/service/access_control.h"
#include "server/service/session.h"
#include "server/service/snapshot_hub.h"
#include "server/service/watch_hub.h"

namespace cascade::service {

struct ServiceOptions {
  std::filesystem::path data_dir;  // simulations/{id}/journal.jsonl under it
  int threads = 0;                 // OpenMP threads per solver thread; 0: OpenMP's default
  Device device = Device::cpu;
  Precision precision = kBuildPrecision;
  std::size_t max_particles = 2'000'000;  // per simulation
  std::size_t max_simulations = 8;        // held at once (any state)
  AccessControl access;
  EngineFactory make_engine;              // empty: cascade::make_engine
  // Set: the engine factory of each session, given its case (a server split over processes,
  // server/parallel/split_server.h); it takes the place of make_engine.
  std::function<EngineFactory(const v1::ScenarioSpec&)> split_engine;
};

class SimulationService final : public v1::SimulationService::CallbackService {
 public:
  explicit SimulationService(ServiceOptions options);
  ~SimulationService() override;

  // Stops every simulation (a running one pauses; a running or paused one writes a checkpoint;
  // each journal ends with `shutdown`) and ends the
  // watch streams; later requests get UNAVAILABLE.
  void shutdown();

  grpc::ServerUnaryReactor* CreateSimulation(grpc::CallbackServerContext* context,
                                             const v1::CreateSimulationRequest* request,
                                             v1::Simulation* response) override;
  grpc::ServerUnaryReactor* GetSimulation(grpc::CallbackServerContext* context, const v1::GetSimulationRequest* request,
                                          v1::Simulation* response) override;
  grpc::ServerUnaryReactor* ListSimulations(grpc::CallbackServerContext* context,
                                            const v1::ListSimulationsRequest* request,
                                            v1::ListSimulationsResponse* response) override;
  grpc::ServerUnaryReactor* DeleteSimulation(grpc::CallbackServerContext* context,
                                             const v1::DeleteSimulationRequest* request,
                                             google::protobuf::Empty* response) override;
  grpc::ServerUnaryReactor* StartSimulation(grpc::CallbackServerContext* context,
                                            const v1::StartSimulationRequest* request,
                                            v1::Simulation* response) override;
  grpc::ServerUnaryReactor* PauseSimulation(grpc::CallbackServerContext* context,
                                            const v1::PauseSimulationRequest* request,
                                            v1::Simulation* response) override;
  grpc::ServerUnaryReactor* ResumeSimulation(grpc::CallbackServerContext* context,
                                             const v1::ResumeSimulationRequest* request,
                                             v1::Simulation* response) override;
  grpc::ServerUnaryReactor* StepSimulation(grpc::CallbackServerContext* context,
                                           const v1::StepSimulationRequest* request,
                                           v1::Simulation* response) override;
  grpc::ServerUnaryReactor* RunSimulationUntil(grpc::CallbackServerContext* context,
                                               const v1::RunSimulationUntilRequest* request,
                                               v1::Simulation* response) override;
  grpc::ServerUnaryReactor* UpdateForcing(grpc::CallbackServerContext* context,
                                          const v1::UpdateForcingRequest* request,
                                          v1::UpdateForcingResponse* response) override;
  grpc::ServerUnaryReactor* AdvanceStage(grpc::CallbackServerContext* context, const v1::AdvanceStageRequest* request,
                                         v1::Simulation* response) override;
  grpc::ServerWriteReactor<v1::FieldChunk>* QueryFields(grpc::CallbackServerContext* context,
                                                        const v1::QueryFieldsRequest* request) override;
  grpc::ServerUnaryReactor* ListProbes(grpc::CallbackServerContext* context, const v1::ListProbesRequest* request,
                                       v1::ListProbesResponse* response) override;
  grpc::ServerUnaryReactor* ListEvents(grpc::CallbackServerContext* context, const v1::ListEventsRequest* request,
                                       v1::ListEventsResponse* response) override;
  grpc::ServerWriteReactor<v1::WatchSimulationResponse>* WatchSimulation(
      grpc::CallbackServerContext* context, const v1::WatchSimulationRequest* request) override;
  grpc::ServerUnaryReactor* RenderSnapshot(grpc::CallbackServerContext* context,
                                           const v1::RenderSnapshotRequest* request,
                                           v1::SnapshotImage* response) override;
  grpc::ServerWriteReactor<v1::SnapshotImage>* StreamSnapshots(grpc::CallbackServerContext* context,
                                                               const v1::StreamSnapshotsRequest* request) override;
  // Checkpoints (checkpoint_methods.cpp).
  grpc::ServerUnaryReactor* CreateCheckpoint(grpc::CallbackServerContext* context,
                                             const v1::CreateCheckpointRequest* request,
                                             v1::Checkpoint* response) override;
  grpc::ServerUnaryReactor* ListCheckpoints(grpc::CallbackServerContext* context,
                                            const v1::ListCheckpointsRequest* request,
                                            v1::ListCheckpointsResponse* response) override;
  grpc::ServerUnaryReactor* RestoreCheckpoint(grpc::CallbackServerContext* context,
                                              const v1::RestoreCheckpointRequest* request,
                                              v1::Simulation* response) override;
  grpc::ServerUnaryReactor* ForkSimulation(grpc::CallbackServerContext* context, const v1::ForkSimulationRequest* request,
                                           v1::Simulation* response) override;

 private:
  // Authorises the caller, then refuses a request with fields this server does not know
  // (check_known_fields). Every method starts with it.
  grpc::Status admit(const grpc::CallbackServerContext& context, const google::protobuf::Message& request, Role needed,
                     Caller& caller) const;
  // admit(), then finds the simulation named `name`: INVALID_ARGUMENT for a malformed name,
  // NOT_FOUND for an unknown one.
  grpc::Status lookup(const grpc::CallbackServerContext& context, const google::protobuf::Message& request,
                      const std::string& name, Role needed, Caller& caller, std::shared_ptr<Session>& session) const;
  // The run-control methods: look up, then `command(session, caller, done)`; the reply is the
  // Simulation once the command is done.
  template <typename Command>
  grpc::ServerUnaryReactor* control(grpc::CallbackServerContext* context, const google::protobuf::Message& request,
                                    const std::string& name, v1::Simulation* response, Command command);
  grpc::Status create(const grpc::CallbackServerContext& context, const v1::CreateSimulationRequest& request,
                      v1::Simulation& response);
  std::string new_id() const;  // under mutex_
  // ForkSimulation's second half, on the parent's solver thread: the fork's session from `source`
  // under the reserved id, its forcing change queued; `finish` replies.
  void start_fork(const std::string& id, const Session& parent, std::shared_ptr<RestoreSource> source,
                  const v1::ForkSimulationRequest& request, const std::string& caller,
                  std::function<void(const grpc::Status&, const v1::Simulation&)> finish);
  grpc::Status restore(const grpc::CallbackServerContext& context, const v1::RestoreCheckpointRequest& request,
                       v1::Simulation& response);
  // The session of a simulation's engine from its spec, as CreateSimulation and RestoreCheckpoint
  // build it. Throws CaseError.
  SessionConfig session_config(const std::string& id, v1::ScenarioSpec spec, const std::string& caller) const;

  const ServiceOptions options_;
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Session>> sessions_;  // by id
  bool shutting_down_ = false;
  WatchHub watch_hub_;
  SnapshotHub snapshot_hub_;
};

}  // namespace cascade::service
