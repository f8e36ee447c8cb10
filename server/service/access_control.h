// Who may call what: bearer tokens from a token file, each with a role. Viewers may read (get,
// list, query, probes, events, watch); operators may also create, control, steer and delete.
//
// Token file: one `NAME ROLE TOKEN` per line (ROLE viewer or operator), `#` starts a comment.
// A client sends `authorization: Bearer TOKEN`. Without a token file every caller is an operator
// named "local" (the loopback default).
#pragma once

#include <grpcpp/server_context.h>
#include <grpcpp/support/status.h>

#include <filesystem>
#include <map>
#include <string>

namespace cascade::service {

enum class Role { viewer, operator_ };

struct Caller {
  std::string name;
  Role role = Role::viewer;
};

class AccessControl {
 public:
  AccessControl() = default;  // open: no token file
  // Throws std::runtime_error naming the file and line of a malformed entry.
  static AccessControl from_file(const std::filesystem::path& path);

  // UNAUTHENTICATED without a known token, PERMISSION_DENIED when the token's role is below `needed`.
  grpc::Status authorize(const grpc::ServerContextBase& context, Role needed, Caller& caller) const;

 private:
  bool open_ = true;
  std::map<std::string, Caller> callers_;  // by token
};

}  // namespace cascade::service
