// Checks of the snapshot RPCs' requests against the simulation they name, and their renderer
// settings. Errors are INVALID_ARGUMENT with a message that starts with the field
// (`snapshot.width: ...`, `every_wall_seconds: ...`), like every request check (request_validation.h).
#pragma once

#include <grpcpp/support/status.h>

#include "cascade/v1/simulation.pb.h"
#include "render/snapshot_settings.h"

namespace cascade::service {

constexpr double kMinSnapshotWallInterval = 0.05, kMaxSnapshotWallInterval = 3600;  // s of wall time

// `requested` checked as a case's output.snapshots entry of `spec` (field, phase, camera, range,
// size up to 3840 × 2160, ...), with the case defaults, as renderer settings.
grpc::Status snapshot_settings_for(const v1::ScenarioSpec& spec, const v1::Snapshot& requested,
                                   render::SnapshotSettings& settings);

// The stream's interval: one of every_simulated_seconds (> 0, finite) or every_wall_seconds.
grpc::Status check_snapshot_interval(const v1::StreamSnapshotsRequest& request);

}  // namespace cascade::service
