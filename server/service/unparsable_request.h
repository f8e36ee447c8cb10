// Requests whose bytes do not parse. gRPC 1.51's callback handlers answer a request that does not
// deserialise into its message with UNIMPLEMENTED and an empty message (RunHandler in
// grpcpp/impl/codegen/server_callback_handlers.h), as if the method did not exist; a client then
// cannot tell a malformed request from a wrong server. The interceptor below turns that answer, on
// a method of cascade.v1, into INVALID_ARGUMENT naming the method. Methods that do not exist keep
// their UNIMPLEMENTED (they have no handler, so no interceptor is made for them here).
#pragma once

#include <grpcpp/support/server_interceptor.h>

#include <memory>

namespace cascade::service {

std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> unparsable_request_interceptors();

}  // namespace cascade::service
