#include "server/service/request_validation.h"

#include <google/protobuf/message.h>
#include <google/protobuf/unknown_field_set.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "server/scenario/forcing_message.h"
#include "server/scenario/plausible_ranges.h"

namespace cascade::service {

namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// A box of `components` finite coordinates each, min < max on every axis.
grpc::Status check_box(const std::string& field, const v1::Box& box, int components) {
  if (box.min_size() != components || box.max_size() != components)
    return invalid(field, "needs " + std::to_string(components) + " components in min and max, got " +
                              std::to_string(box.min_size()) + " and " + std::to_string(box.max_size()));
  for (int a = 0; a < components; ++a) {
    const std::string axis = "[" + std::to_string(a) + "]";
    if (!std::isfinite(box.min(a))) return invalid(field + ".min" + axis, "is not a finite number");
    if (!std::isfinite(box.max(a))) return invalid(field + ".max" + axis, "is not a finite number");
    if (!(box.min(a) < box.max(a)))
      return invalid(field + ".max" + axis, "must exceed min" + axis + " (" + number(box.min(a)) + ")");
  }
  return grpc::Status::OK;
}

// check_known_fields of the message held by the field `path` ("request" at the top).
grpc::Status check_known_fields(const google::protobuf::Message& message, const std::string& path) {
  const google::protobuf::Reflection& reflection = *message.GetReflection();
  if (const auto& unknown = reflection.GetUnknownFields(message); !unknown.empty()) {
    const std::string number = std::to_string(unknown.field(0).number());
    return invalid(path, "unknown field number " + number + " (" + message.GetDescriptor()->full_name() +
                             " has no field " + number + " in this server; is the client newer?)");
  }
  std::vector<const google::protobuf::FieldDescriptor*> fields;
  reflection.ListFields(message, &fields);
  for (const auto* field : fields) {
    if (field->cpp_type() != google::protobuf::FieldDescriptor::CPPTYPE_MESSAGE) continue;
    const std::string inner = path == "request" ? field->name() : path + "." + field->name();
    if (!field->is_repeated()) {
      if (auto status = check_known_fields(reflection.GetMessage(message, field), inner); !status.ok()) return status;
      continue;
    }
    for (int k = 0; k < reflection.FieldSize(message, field); ++k)
      if (auto status = check_known_fields(reflection.GetRepeatedMessage(message, field, k),
                                           inner + "[" + std::to_string(k) + "]");
          !status.ok())
        return status;
  }
  return grpc::Status::OK;
}

}  // namespace

grpc::Status check_known_fields(const google::protobuf::Message& request) {
  return check_known_fields(request, "request");
}

grpc::Status invalid(const std::string& field, const std::string& message) {
  return {grpc::StatusCode::INVALID_ARGUMENT, field + ": " + message};
}

grpc::Status check_simulation_id(const std::string& field, const std::string& id) {
  const bool allowed = !id.empty() && id.size() <= 63 && id.front() != '-' &&
                       std::all_of(id.begin(), id.end(), [](char c) {
                         return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
                       });
  if (!allowed) return invalid(field, "an id is 1 to 63 characters of a-z, 0-9 and '-', not starting with '-'");
  return grpc::Status::OK;
}

grpc::Status check_simulation_name(const std::string& field, const std::string& name, std::string& id) {
  const std::string prefix = "simulations/";
  if (name.rfind(prefix, 0) != 0)
    return invalid(field, "must be simulations/{id}, got '" + name.substr(0, 80) + "'");
  id = name.substr(prefix.size());
  return check_simulation_id(field, id);
}

grpc::Status check_step(const v1::StepSimulationRequest& request) {
  if (request.steps() < 1 || request.steps() > kMaxStepsPerRequest)
    return invalid("steps", "must be from 1 to " + std::to_string(kMaxStepsPerRequest) + ", got " +
                                std::to_string(request.steps()));
  return grpc::Status::OK;
}

grpc::Status check_run_until(const v1::RunSimulationUntilRequest& request, double end_time) {
  if (!std::isfinite(request.time())) return invalid("time", "is not a finite number");
  if (!(request.time() > 0) || request.time() > end_time)
    return invalid("time", "must be in (0, end_time = " + number(end_time) + "] s, got " + number(request.time()));
  if (request.has_stop_after_event()) {
    const auto& stop = request.stop_after_event();
    const std::array<const char*, 5> kinds = {"ponding_started", "landslide_onset", "water_impact", "wave_at_gauge",
                                              "overtopping"};
    if (std::find(kinds.begin(), kinds.end(), stop.kind()) == kinds.end())
      return invalid("stop_after_event.kind", "'" + stop.kind().substr(0, 80) +
                                                  "' is not a cascade event (ponding_started, landslide_onset, "
                                                  "water_impact, wave_at_gauge, overtopping)");
    if (!std::isfinite(stop.seconds()) || stop.seconds() < 0)
      return invalid("stop_after_event.seconds", "must be a finite number >= 0, got " + number(stop.seconds()));
  }
  return grpc::Status::OK;
}

grpc::Status check_update_forcing(const v1::UpdateForcingRequest& request, const v1::Forcing& current,
                                  int dimensions, double end_time) {
  const auto& paths = request.update_mask().paths();
  if (paths.empty()) return invalid("update_mask", "names no field (steerable: rainfall.intensity, rainfall.factor, rainfall.region, ponding.p_max, ponding.p_min)");
  bool p_max_set = false, p_min_set = false;
  for (int k = 0; k < paths.size(); ++k) {
    const std::string& path = paths[k];
    const std::string field = "update_mask.paths[" + std::to_string(k) + "]";
    if (std::find(kSteerableForcingFields.begin(), kSteerableForcingFields.end(), path) == kSteerableForcingFields.end())
      return invalid(field, "'" + path.substr(0, 80) + "' is not steerable (rainfall.intensity, rainfall.factor, rainfall.region, ponding.p_max, ponding.p_min)");
    if (std::count(paths.begin(), paths.end(), path) > 1) return invalid(field, "'" + path + "' is named twice");
    const auto& f = request.forcing();
    if (path == "rainfall.intensity") {
      const double i = f.rainfall().intensity();
      if (!std::isfinite(i)) return invalid("forcing.rainfall.intensity", "is not a finite number");
      if (const auto message = implausible(kRainfallIntensity, i)) return invalid("forcing.rainfall.intensity", *message);
    } else if (path == "rainfall.factor") {
      if (std::count(paths.begin(), paths.end(), "rainfall.intensity") > 0)
        return invalid(field, "rainfall.factor scales the case's rain and rainfall.intensity replaces it: not both");
      if (!f.rainfall().has_factor()) return invalid("forcing.rainfall.factor", "is not set");
      const double factor = f.rainfall().factor();
      if (!std::isfinite(factor)) return invalid("forcing.rainfall.factor", "is not a finite number");
      if (const auto message = implausible(kRainFactor, factor)) return invalid("forcing.rainfall.factor", *message);
    } else if (path == "rainfall.region" && f.rainfall().has_region()) {
      const auto status = check_box("forcing.rainfall.region", f.rainfall().region(), dimensions);
      if (!status.ok()) return status;
    } else if (path == "ponding.p_max") {
      const double p = f.ponding().p_max();
      if (!std::isfinite(p)) return invalid("forcing.ponding.p_max", "is not a finite number");
      if (const auto message = implausible(kSurfacePressure, p)) return invalid("forcing.ponding.p_max", *message);
      p_max_set = true;
    } else if (path == "ponding.p_min" && f.ponding().has_p_min()) {
      const double p = f.ponding().p_min();
      if (!std::isfinite(p)) return invalid("forcing.ponding.p_min", "is not a finite number");
      if (const auto message = implausible(kSurfacePressure, p)) return invalid("forcing.ponding.p_min", *message);
      p_min_set = true;
    }
  }
  const double p_max = p_max_set ? request.forcing().ponding().p_max() : current.ponding().p_max();
  const bool has_p_min = p_min_set || (current.ponding().has_p_min() &&
                                       std::find(paths.begin(), paths.end(), "ponding.p_min") == paths.end());
  const double p_min = p_min_set ? request.forcing().ponding().p_min() : current.ponding().p_min();
  if (has_p_min && !(p_min < p_max))
    return invalid(p_min_set ? "forcing.ponding.p_min" : "forcing.ponding.p_max",
                   "the drying limit p_min (" + number(p_min) + " Pa) must stay below p_max (" + number(p_max) + " Pa)");
  if (request.has_effective_time()) {
    const double t = request.effective_time();
    if (!std::isfinite(t) || t < 0 || t > end_time)
      return invalid("effective_time", "must be in [0, end_time = " + number(end_time) + "] s, got " + number(t));
  }
  return grpc::Status::OK;
}

grpc::Status check_fork(const v1::ForkSimulationRequest& request, const v1::Forcing& current, int dimensions,
                        double end_time) {
  if (!request.simulation_id().empty())
    if (auto status = check_simulation_id("simulation_id", request.simulation_id()); !status.ok()) return status;
  if (request.update_mask().paths().empty()) {
    if (request.forcing().ByteSizeLong() > 0) return invalid("update_mask", "names no field, so `forcing` would be ignored");
    return grpc::Status::OK;
  }
  // UpdateForcing's checks, whose field names (forcing.*, update_mask.paths[k]) are this request's.
  v1::UpdateForcingRequest change;
  *change.mutable_forcing() = request.forcing();
  *change.mutable_update_mask() = request.update_mask();
  return check_update_forcing(change, current, dimensions, end_time);
}

grpc::Status check_advance_stage(const v1::AdvanceStageRequest& request) {
  const std::string& reason = request.reason();
  if (reason.size() > kMaxReasonBytes)
    return invalid("reason", "at most " + std::to_string(kMaxReasonBytes) + " bytes, got " + std::to_string(reason.size()));
  const auto control = std::find_if(reason.begin(), reason.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
  });
  if (control != reason.end())
    return invalid("reason", "holds a control character (code " +
                                 std::to_string(static_cast<unsigned char>(*control)) + ") at byte " +
                                 std::to_string(control - reason.begin()));
  return grpc::Status::OK;
}

grpc::Status check_query(const v1::QueryFieldsRequest& request) {
  const std::string& phase = request.phase();
  if (!phase.empty() && phase != "water" && phase != "soil" && phase != "boundary")
    return invalid("phase", "must be water, soil, boundary or empty (all), not '" + phase.substr(0, 80) + "'");
  if (request.has_box()) {
    const auto status = check_box("box", request.box(), 3);
    if (!status.ok()) return status;
  }
  if (request.stride() > kMaxStride)
    return invalid("stride", "must be at most " + std::to_string(kMaxStride) + ", got " + std::to_string(request.stride()));
  if (request.fields_size() > 64) return invalid("fields", "at most 64 names");
  return grpc::Status::OK;
}

grpc::Status check_since_time(double since_time) {
  if (std::isnan(since_time)) return invalid("since_time", "is NaN");
  return grpc::Status::OK;
}

grpc::Status check_watch(const v1::WatchSimulationRequest& request) {
  const double s = request.interval_seconds();
  if (!std::isfinite(s)) return invalid("interval_seconds", "is not a finite number");
  if (s != 0 && (s < kMinWatchInterval || s > kMaxWatchInterval))
    return invalid("interval_seconds", "must be 0 (1 s) or in [0.05, 3600], got " + number(s));
  return grpc::Status::OK;
}

}  // namespace cascade::service
