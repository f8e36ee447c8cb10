// Checks of request fields that need no simulation state. Each returns OK or INVALID_ARGUMENT
// with a message that starts with the field's name (`steps: ...`, `forcing.rainfall.intensity:
// ...`), so a client can tell which field to fix.
#pragma once

#include <google/protobuf/message.h>
#include <grpcpp/support/status.h>

#include <string>

#include "cascade/v1/simulation.pb.h"

namespace cascade::service {

// Largest values accepted; beyond them a request is taken for a mistake.
constexpr std::uint64_t kMaxStepsPerRequest = 10'000'000;
constexpr std::uint32_t kMaxStride = 1'000'000;
constexpr std::size_t kMaxCaseYamlBytes = 1 << 20;
constexpr double kMinWatchInterval = 0.05, kMaxWatchInterval = 3600;  // s of wall time
constexpr std::size_t kMaxReasonBytes = 500;  // an operator's note; the journal keeps one line per entry

grpc::Status invalid(const std::string& field, const std::string& message);

// A field this server does not know (a newer client's, or a mistake) would otherwise be dropped
// silently, and the caller would believe that a setting applied. Checks `request` and every
// message inside it: `forcing.rainfall: unknown field number 17 (...)`.
grpc::Status check_known_fields(const google::protobuf::Message& request);

// `name` is simulations/{id} with a valid id; `id` receives it.
grpc::Status check_simulation_name(const std::string& field, const std::string& name, std::string& id);
// [a-z0-9-], 1 to 63 characters, starting with a letter or digit.
grpc::Status check_simulation_id(const std::string& field, const std::string& id);

grpc::Status check_step(const v1::StepSimulationRequest& request);
grpc::Status check_run_until(const v1::RunSimulationUntilRequest& request, double end_time);
// `current`: the forcing now, for the p_min < p_max check of a change that names only one of them.
grpc::Status check_update_forcing(const v1::UpdateForcingRequest& request, const v1::Forcing& current,
                                  int dimensions, double end_time);
// The fork's id (optional) and its forcing change, as check_update_forcing's without a time; a
// forcing without a mask is refused, since it would be ignored.
grpc::Status check_fork(const v1::ForkSimulationRequest& request, const v1::Forcing& current, int dimensions,
                        double end_time);
// `reason`: at most kMaxReasonBytes, no control characters (it goes into one journal line and the
// events that clients print a line each).
grpc::Status check_advance_stage(const v1::AdvanceStageRequest& request);
// The field names are checked against the frame, once it is taken (field_query.h).
grpc::Status check_query(const v1::QueryFieldsRequest& request);
grpc::Status check_since_time(double since_time);
grpc::Status check_watch(const v1::WatchSimulationRequest& request);

}  // namespace cascade::service
