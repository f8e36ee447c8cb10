// SimulationService::ForkSimulation: a what-if branch of a simulation. The parent takes the fork's
// source at its next step boundary (Session::fork: a clone of its engine, the journal so far and
// the history clients saw); the fork is then a session that starts from it, PAUSED at that step,
// under an id reserved before the parent was asked, with its forcing change queued first so that
// it applies before the fork's first step. Its journal is the parent's up to the
// fork, then its own: `cascade run CASE --replay` of it repeats the fork.
#include <filesystem>
#include <optional>

#include "server/service/request_validation.h"
#include "server/service/simulation_service.h"

namespace cascade::service {

namespace {

const std::string kNamePrefix = "simulations/";

}  // namespace

grpc::ServerUnaryReactor* SimulationService::ForkSimulation(grpc::CallbackServerContext* context,
                                                            const v1::ForkSimulationRequest* request,
                                                            v1::Simulation* response) {
  auto* reactor = context->DefaultReactor();
  const auto refuse = [&](const grpc::Status& status) {
    reactor->Finish(status);
    return reactor;
  };
  Caller caller;
  std::shared_ptr<Session> parent;
  if (auto status = lookup(*context, *request, request->name(), Role::operator_, caller, parent); !status.ok())
    return refuse(status);
  if (auto status =
          check_fork(*request, parent->describe().forcing(), parent->spec().dimensions(), parent->spec().end_time());
      !status.ok())
    return refuse(status);

  // The fork's id is reserved by its directory (new_id and CreateSimulation skip existing ones).
  std::string id;
  {
    std::lock_guard lock(mutex_);
    if (shutting_down_) return refuse({grpc::StatusCode::UNAVAILABLE, "the server is shutting down"});
    if (sessions_.size() >= options_.max_simulations)
      return refuse({grpc::StatusCode::RESOURCE_EXHAUSTED,
                     "simulations: the server holds " + std::to_string(sessions_.size()) +
                         ", its limit (--max-simulations); delete one first"});
    id = request->simulation_id().empty() ? new_id() : request->simulation_id();
    const auto directory = options_.data_dir / "simulations" / id;
    if (sessions_.count(id) || std::filesystem::exists(directory))
      return refuse({grpc::StatusCode::ALREADY_EXISTS, "simulation_id: simulations/" + id + " exists"});
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error) return refuse({grpc::StatusCode::INTERNAL, "cannot create " + directory.string() + ": " + error.message()});
  }

  // The callback runs on the parent's solver thread, which holds the parent alive: a raw pointer,
  // so that the parent's queue never holds the last reference to its own session.
  Session* parent_raw = parent.get();
  const v1::ForkSimulationRequest checked = *request;
  const auto finish = [reactor, response](const grpc::Status& status, const v1::Simulation& fork) {
    if (status.ok()) *response = fork;
    reactor->Finish(status);
  };
  parent->fork(kNamePrefix + id, caller.name,
               [this, id, parent_raw, checked, caller = caller.name, finish](const grpc::Status& status,
                                                                             std::shared_ptr<RestoreSource> source) {
                 if (!status.ok()) {
                   std::error_code ignored;
                   std::filesystem::remove(options_.data_dir / "simulations" / id, ignored);  // empty still
                   return finish(status, {});
                 }
                 start_fork(id, *parent_raw, std::move(source), checked, caller, finish);
               });
  return reactor;
}

void SimulationService::start_fork(const std::string& id, const Session& parent, std::shared_ptr<RestoreSource> source,
                                   const v1::ForkSimulationRequest& request, const std::string& caller,
                                   std::function<void(const grpc::Status&, const v1::Simulation&)> finish) {
  SessionConfig config = parent.config();  // spec, engine and the shared initial particles
  config.name = kNamePrefix + id;
  config.directory = options_.data_dir / "simulations" / id;
  config.caller = caller;
  config.restore = std::move(source);
  auto fork = std::make_shared<Session>(std::move(config));
  {
    std::lock_guard lock(mutex_);
    if (shutting_down_) return finish({grpc::StatusCode::UNAVAILABLE, "the server is shutting down"}, {});
    if (!sessions_.emplace(id, fork).second)
      return finish({grpc::StatusCode::ABORTED, "simulation_id: simulations/" + id + " was created meanwhile"}, {});
  }
  const auto& paths = request.update_mask().paths();
  if (paths.empty()) return finish(grpc::Status::OK, fork->describe());
  Session* fork_raw = fork.get();  // the callback runs on the fork's solver thread, or here
  fork->update_forcing(request.forcing(), {paths.begin(), paths.end()}, std::nullopt, caller,
                       [fork_raw, finish](const Session::Outcome& outcome) { finish(outcome.status, fork_raw->describe()); });
}

}  // namespace cascade::service
