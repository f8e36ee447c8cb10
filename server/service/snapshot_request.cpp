#include "server/service/snapshot_request.h"

#include <cmath>

#include "server/io/snapshot_writer.h"
#include "server/scenario/case_validation.h"
#include "server/scenario/number_text.h"
#include "server/service/request_validation.h"

namespace cascade::service {

namespace {

// The first problem the case checks find, with the key that names the request field.
struct SnapshotProblem {
  std::string key, message;
};


}  // namespace

grpc::Status snapshot_settings_for(const v1::ScenarioSpec& spec, const v1::Snapshot& requested,
                                   render::SnapshotSettings& settings) {
  try {
    check_snapshot(spec, "snapshot", requested,
                   [](const std::string& key, const std::string& message) { throw SnapshotProblem{key, message}; });
  } catch (const SnapshotProblem& problem) {
    return invalid(problem.key, problem.message);
  }
  v1::Snapshot snapshot = requested;
  apply_snapshot_defaults(snapshot, spec.dimensions());
  settings = snapshot_settings(snapshot, spec.dimensions(), spec.dp());
  return grpc::Status::OK;
}

grpc::Status check_snapshot_interval(const v1::StreamSnapshotsRequest& request) {
  switch (request.interval_case()) {
    case v1::StreamSnapshotsRequest::kEverySimulatedSeconds: {
      const double s = request.every_simulated_seconds();
      if (!(std::isfinite(s) && s > 0)) return invalid("every_simulated_seconds", "must be a finite number > 0, got " + number_text(s));
      return grpc::Status::OK;
    }
    case v1::StreamSnapshotsRequest::kEveryWallSeconds: {
      const double s = request.every_wall_seconds();
      if (!(s >= kMinSnapshotWallInterval && s <= kMaxSnapshotWallInterval))
        return invalid("every_wall_seconds", "must be in [0.05, 3600], got " + number_text(s));
      return grpc::Status::OK;
    }
    default:
      return invalid("interval", "give every_simulated_seconds or every_wall_seconds");
  }
}

}  // namespace cascade::service
