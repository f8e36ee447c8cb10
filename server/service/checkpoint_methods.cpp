// SimulationService's checkpoint methods: CreateCheckpoint, ListCheckpoints, RestoreCheckpoint.
#include <filesystem>

#include "server/scenario/case_error.h"
#include "server/service/checkpoint_store.h"
#include "server/service/request_validation.h"
#include "server/service/simulation_service.h"

namespace cascade::service {

namespace {

grpc::ServerUnaryReactor* reply(grpc::CallbackServerContext* context, const grpc::Status& status) {
  auto* reactor = context->DefaultReactor();
  reactor->Finish(status);
  return reactor;
}

// lookup() names its field `name`; a collection method's is `parent`.
grpc::Status about_parent(const grpc::Status& status) {
  const std::string& message = status.error_message();
  if (message.rfind("name:", 0) != 0) return status;
  return {status.error_code(), "parent" + message.substr(4)};
}

}  // namespace

grpc::ServerUnaryReactor* SimulationService::CreateCheckpoint(grpc::CallbackServerContext* context,
                                                              const v1::CreateCheckpointRequest* request,
                                                              v1::Checkpoint* response) {
  Caller caller;
  std::shared_ptr<Session> session;
  if (auto status = lookup(*context, *request, request->parent(), Role::operator_, caller, session); !status.ok())
    return reply(context, about_parent(status));
  auto* reactor = context->DefaultReactor();
  const std::string name = session->name();
  session->checkpoint(caller.name, [reactor, response, name](const grpc::Status& status, const std::filesystem::path& path) {
    if (!status.ok()) return reactor->Finish(status);
    try {
      *response = describe_checkpoint(name, path);
      reactor->Finish(grpc::Status::OK);
    } catch (const std::exception& e) {
      reactor->Finish({grpc::StatusCode::INTERNAL, e.what()});
    }
  });
  return reactor;
}

grpc::ServerUnaryReactor* SimulationService::ListCheckpoints(grpc::CallbackServerContext* context,
                                                             const v1::ListCheckpointsRequest* request,
                                                             v1::ListCheckpointsResponse* response) {
  Caller caller;
  if (auto status = admit(*context, *request, Role::viewer, caller); !status.ok()) return reply(context, status);
  std::string id;
  if (auto status = check_simulation_name("parent", request->parent(), id); !status.ok()) return reply(context, status);
  const auto directory = options_.data_dir / "simulations" / id;
  if (!std::filesystem::is_directory(directory))
    return reply(context, {grpc::StatusCode::NOT_FOUND, "parent: no simulation " + request->parent()});
  try {
    for (auto& c : list_checkpoints(request->parent(), directory)) *response->add_checkpoints() = std::move(c);
  } catch (const std::exception& e) {
    return reply(context, {grpc::StatusCode::DATA_LOSS, e.what()});
  }
  return reply(context, grpc::Status::OK);
}

grpc::ServerUnaryReactor* SimulationService::RestoreCheckpoint(grpc::CallbackServerContext* context,
                                                               const v1::RestoreCheckpointRequest* request,
                                                               v1::Simulation* response) {
  return reply(context, restore(*context, *request, *response));
}

grpc::Status SimulationService::restore(const grpc::CallbackServerContext& context,
                                        const v1::RestoreCheckpointRequest& request, v1::Simulation& response) {
  Caller caller;
  if (auto status = admit(context, request, Role::operator_, caller); !status.ok()) return status;
  std::string id, checkpoint_id;
  if (auto status = parse_checkpoint_name("name", request.name(), id, checkpoint_id); !status.ok()) return status;
  const auto path = checkpoint_directory(options_.data_dir / "simulations" / id) / (checkpoint_id + ".h5");
  if (!std::filesystem::is_regular_file(path)) return {grpc::StatusCode::NOT_FOUND, "name: no checkpoint " + request.name()};

  auto source = std::make_shared<RestoreSource>();
  source->checkpoint_name = request.name();
  SessionConfig session;
  try {
    source->checkpoint = read_checkpoint(path);
    const bool single = options_.precision == Precision::single_precision;
    if (source->checkpoint.engine.single_precision != single)
      return {grpc::StatusCode::FAILED_PRECONDITION,
              "name: the checkpoint is of a " + std::string(single ? "double" : "float") +
                  " engine; this server runs " + (single ? "float" : "double")};
    session = session_config(id, source->checkpoint.spec, caller.name);
  } catch (const CaseError& e) {
    return {grpc::StatusCode::DATA_LOSS, "name: the checkpoint's case no longer builds: " + std::string(e.what())};
  } catch (const std::exception& e) {
    return {grpc::StatusCode::DATA_LOSS, "name: " + std::string(e.what())};
  }
  session.restore = std::move(source);

  std::shared_ptr<Session> replaced;
  {
    std::lock_guard lock(mutex_);
    if (shutting_down_) return {grpc::StatusCode::UNAVAILABLE, "the server is shutting down"};
    const auto found = sessions_.find(id);
    if (found == sessions_.end() && sessions_.size() >= options_.max_simulations)
      return {grpc::StatusCode::RESOURCE_EXHAUSTED,
              "simulations: the server holds " + std::to_string(sessions_.size()) +
                  ", its limit (--max-simulations); delete one first"};
    if (found != sessions_.end()) {
      replaced = found->second;
      sessions_.erase(found);
    }
  }
  // The simulation being replaced ends at its current step, its journal with `restore`; then the
  // restored one takes its name (journal.jsonl included, session.h).
  if (replaced) replaced->stop("restore", caller.name);
  auto restored = std::make_shared<Session>(std::move(session));
  response = restored->describe();
  std::lock_guard lock(mutex_);
  if (!sessions_.emplace(id, restored).second)
    return {grpc::StatusCode::ABORTED, "name: " + restored->name() + " was restored or created meanwhile"};
  return grpc::Status::OK;
}

}  // namespace cascade::service
