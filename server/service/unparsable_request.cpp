#include "server/service/unparsable_request.h"

#include <google/protobuf/descriptor.h>

#include <string>
#include <utility>

namespace cascade::service {
namespace {

using grpc::experimental::InterceptionHookPoints;

class UnparsableRequest final : public grpc::experimental::Interceptor {
 public:
  explicit UnparsableRequest(std::string method) : method_(std::move(method)) {}

  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::PRE_SEND_STATUS)) {
      const grpc::Status status = methods->GetSendStatus();
      // Every handler of the service answers with a message: an empty UNIMPLEMENTED on one of its
      // methods is gRPC's answer to a request that did not deserialise.
      if (status.error_code() == grpc::StatusCode::UNIMPLEMENTED && status.error_message().empty())
        methods->ModifySendStatus(grpc::Status(
            grpc::StatusCode::INVALID_ARGUMENT,
            "request: the bytes do not parse as the request message of " + method_ +
                " (a truncated or corrupted message, a field of the wrong type, or a string that is not UTF-8)"));
    }
    methods->Proceed();
  }

 private:
  std::string method_;
};

class UnparsableRequestFactory final : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  grpc::experimental::Interceptor* CreateServerInterceptor(grpc::experimental::ServerRpcInfo* info) override {
    const std::string method = info->method() ? info->method() : "";
    return method_of_cascade(method) ? new UnparsableRequest(method) : nullptr;
  }

 private:
  // "/cascade.v1.SimulationService/GetSimulation": a method that cascade.v1 defines (not a health
  // check, not reflection, not a name that no service has).
  static bool method_of_cascade(const std::string& path) {
    const auto slash = path.rfind('/');
    if (path.rfind("/cascade.v1.", 0) != 0 || slash == 0 || slash == std::string::npos) return false;
    const std::string full_name = path.substr(1, slash - 1) + "." + path.substr(slash + 1);
    return google::protobuf::DescriptorPool::generated_pool()->FindMethodByName(full_name) != nullptr;
  }
};

}  // namespace

std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> unparsable_request_interceptors() {
  return std::make_unique<UnparsableRequestFactory>();
}

}  // namespace cascade::service
