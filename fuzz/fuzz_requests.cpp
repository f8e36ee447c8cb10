// libFuzzer target: the server's request checks (server/service/request_validation.h) on any
// bytes. The first byte picks the request type, the rest is parsed as that message; a message that
// parses is checked for unknown fields and then by its method's check, which answers OK or
// INVALID_ARGUMENT with a message naming the field. A crash, an exception, a sanitizer report or an
// INVALID_ARGUMENT without a message is a finding (scripts/fuzz.sh).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "cascade/v1/simulation.pb.h"
#include "server/service/request_validation.h"

namespace {

using namespace cascade;

template <class Request, class Check>
void check(const std::uint8_t* data, std::size_t size, Check check_request) {
  Request request;
  if (!request.ParseFromArray(data, static_cast<int>(size))) return;
  grpc::Status status = service::check_known_fields(request);
  if (status.ok()) status = check_request(request);
  if (!status.ok() && (status.error_code() != grpc::StatusCode::INVALID_ARGUMENT || status.error_message().empty()))
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t kind = data[0] % 9;
  ++data;
  --size;
  const double end_time = 3600;  // a simulation's end time, for the checks that bound times by it
  switch (kind) {
    case 0:
      check<v1::StepSimulationRequest>(data, size, [](const auto& r) { return service::check_step(r); });
      break;
    case 1:
      check<v1::RunSimulationUntilRequest>(data, size,
                                           [&](const auto& r) { return service::check_run_until(r, end_time); });
      break;
    case 2:
      check<v1::UpdateForcingRequest>(data, size, [&](const auto& r) {
        v1::Forcing current;
        current.mutable_ponding()->set_p_max(1e3);
        return service::check_update_forcing(r, current, 2, end_time);
      });
      break;
    case 3:
      check<v1::AdvanceStageRequest>(data, size, [](const auto& r) { return service::check_advance_stage(r); });
      break;
    case 4:
      check<v1::QueryFieldsRequest>(data, size, [](const auto& r) { return service::check_query(r); });
      break;
    case 5:
      check<v1::WatchSimulationRequest>(data, size, [](const auto& r) { return service::check_watch(r); });
      break;
    case 7:
      check<v1::ForkSimulationRequest>(data, size, [&](const auto& r) {
        v1::Forcing current;
        current.mutable_ponding()->set_p_max(1e3);
        return service::check_fork(r, current, 2, end_time);
      });
      break;
    case 6: {
      const std::string name(reinterpret_cast<const char*>(data), size);
      std::string id;
      const auto status = service::check_simulation_name("name", name, id);
      if (!status.ok() && status.error_message().empty()) std::abort();
      break;
    }
    default:
      check<v1::GetSimulationRequest>(data, size, [](const auto& r) {
        std::string id;
        return service::check_simulation_name("name", r.name(), id);
      });
      break;
  }
  return 0;
}
