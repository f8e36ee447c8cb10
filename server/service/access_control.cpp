#include "server/service/access_control.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cascade::service {

AccessControl AccessControl::from_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read token file " + path.string());
  AccessControl access;
  access.open_ = false;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream fields(line);
    std::string name, role, token, extra;
    if (!(fields >> name)) continue;
    const std::string where = path.string() + ":" + std::to_string(number) + ": ";
    if (!(fields >> role >> token) || (fields >> extra))
      throw std::runtime_error(where + "expected NAME ROLE TOKEN");
    if (role != "viewer" && role != "operator")
      throw std::runtime_error(where + "role must be viewer or operator, not '" + role + "'");
    if (token.size() < 16) throw std::runtime_error(where + "a token needs at least 16 characters");
    if (!access.callers_.emplace(token, Caller{name, role == "viewer" ? Role::viewer : Role::operator_}).second)
      throw std::runtime_error(where + "token given twice");
  }
  if (access.callers_.empty()) throw std::runtime_error("token file " + path.string() + " holds no token");
  return access;
}

grpc::Status AccessControl::authorize(const grpc::ServerContextBase& context, Role needed, Caller& caller) const {
  if (open_) {
    caller = {"local", Role::operator_};
    return grpc::Status::OK;
  }
  const auto& metadata = context.client_metadata();
  const auto header = metadata.find("authorization");
  const std::string bearer = "Bearer ";
  if (header == metadata.end())
    return {grpc::StatusCode::UNAUTHENTICATED, "authorization: no bearer token sent"};
  const std::string value(header->second.data(), header->second.size());
  const auto known = value.rfind(bearer, 0) == 0 ? callers_.find(value.substr(bearer.size())) : callers_.end();
  if (known == callers_.end()) return {grpc::StatusCode::UNAUTHENTICATED, "authorization: unknown token"};
  caller = known->second;
  if (needed == Role::operator_ && caller.role != Role::operator_)
    return {grpc::StatusCode::PERMISSION_DENIED, "caller " + caller.name + " is a viewer; this method needs an operator"};
  return grpc::Status::OK;
}

}  // namespace cascade::service
