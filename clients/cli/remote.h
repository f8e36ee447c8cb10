// What the server subcommands of `cascade` share (remote_command.cpp, ensemble_command.cpp): their
// arguments, the connection to the server with its token, and the number and forcing parsers.
#pragma once

#include <google/protobuf/util/json_util.h>
#include <grpcpp/grpcpp.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cascade/v1/simulation.grpc.pb.h"
#include "server/scenario/file_text.h"

namespace cascade::cli {

struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// A subcommand's arguments: positionals, `--key value` options (repeatable) and flags.
struct Arguments {
  std::vector<std::string> positional;
  std::multimap<std::string, std::string> options;
  bool json = false;

  std::string option(const std::string& key, const std::string& fallback = {}) const {
    const auto found = options.find(key);
    return found == options.end() ? fallback : found->second;
  }
  std::vector<std::string> all(const std::string& key) const {
    std::vector<std::string> values;
    for (auto [it, end] = options.equal_range(key); it != end; ++it) values.push_back(it->second);
    return values;
  }
};

inline const std::set<std::string> kValueOptions = {
    "--server", "--token", "--tls-ca", "--set",    "--id",     "--at",   "--interval",  "--phase",     "--box",
    "--stride", "--out",   "--since",  "--field",  "--translucent", "--colour-map", "--min", "--max", "--camera",
    "--azimuth", "--elevation", "--zoom", "--fov", "--eye", "--target", "--width", "--height", "--background",
    "--frames", "--every-sim", "--every-wall", "--count", "--reason", "--rain-factors", "--hyetograph",
    "--time-unit", "--intensity-unit", "--until", "--stop-after"};

inline Arguments parse_arguments(const std::vector<std::string>& args) {
  Arguments a;
  for (std::size_t k = 0; k < args.size(); ++k) {
    if (args[k] == "--json") a.json = true;
    else if (kValueOptions.count(args[k])) {
      if (k + 1 >= args.size()) throw UsageError(args[k] + " needs a value");
      a.options.emplace(args[k], args[k + 1]);
      ++k;
    } else if (args[k].size() > 1 && args[k][0] == '-' && !std::isdigit(static_cast<unsigned char>(args[k][1])))
      throw UsageError("unknown option '" + args[k] + "'");
    else a.positional.push_back(args[k]);
  }
  return a;
}

inline double number(const std::string& what, const std::string& text) {
  std::size_t used = 0;
  try {
    const double v = std::stod(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  throw UsageError(what + " needs a number, got '" + text + "'");
}

// "1,2,3" → {1, 2, 3}.
inline std::vector<double> number_list(const std::string& what, const std::string& text) {
  std::vector<double> v;
  std::stringstream parts(text);
  for (std::string part; std::getline(parts, part, ',');) v.push_back(number(what, part));
  return v;
}

// As number_list, exactly `count` of them.
inline std::vector<double> numbers(const std::string& what, const std::string& text, std::size_t count, const char* form) {
  auto v = number_list(what, text);
  if (v.size() != count) throw UsageError(what + " needs " + form);
  return v;
}

// "X0,Z0,X1,Z1" (2D) or "X0,Y0,Z0,X1,Y1,Z1" (3D) → the box from min to max. The server checks
// that the count matches the simulation's dimensions.
inline v1::Box region(const std::string& what, const std::string& text) {
  const auto v = number_list(what, text);
  if (v.size() != 4 && v.size() != 6) throw UsageError(what + " needs X0,Z0,X1,Z1 (2D) or X0,Y0,Z0,X1,Y1,Z1 (3D), or none");
  v1::Box box;
  const std::size_t half = v.size() / 2;
  for (std::size_t a = 0; a < half; ++a) {
    box.add_min(v[a]);
    box.add_max(v[a + half]);
  }
  return box;
}

inline const std::string kSteerable = "(rainfall.intensity, rainfall.factor, rainfall.region, ponding.p_max, ponding.p_min)";

// One KEY=VALUE of `set` and `fork` into the forcing and its update mask: rainfall.intensity,
// rainfall.factor, ponding.p_max, ponding.p_min (none: no limit), rainfall.region=X0,Z0,X1,Z1
// (none: everywhere). The server checks the values and names the field.
inline void add_forcing(const std::string& command, const std::string& pair, v1::Forcing& forcing,
                        google::protobuf::FieldMask& mask) {
  const auto eq = pair.find('=');
  if (eq == std::string::npos) throw UsageError(command + " needs KEY=VALUE, got '" + pair + "'");
  const std::string key = pair.substr(0, eq), value = pair.substr(eq + 1);
  if (key == "rainfall.intensity") forcing.mutable_rainfall()->set_intensity(number(key, value));
  else if (key == "rainfall.factor") forcing.mutable_rainfall()->set_factor(number(key, value));
  else if (key == "rainfall.region") {
    if (value != "none") *forcing.mutable_rainfall()->mutable_region() = region(key, value);
  } else if (key == "ponding.p_max") forcing.mutable_ponding()->set_p_max(number(key, value));
  else if (key == "ponding.p_min") {
    if (value != "none") forcing.mutable_ponding()->set_p_min(number(key, value));
  } else throw UsageError(command + ": '" + key + "' is not steerable here " + kSteerable);
  mask.add_paths(key);
}

// --stop-after KIND[:SECONDS] (run-until, ensemble): the run ends SECONDS after the first cascade
// event KIND; the server checks the kind. Unset without the option.
inline std::optional<v1::EventStop> event_stop(const Arguments& args) {
  const std::string text = args.option("--stop-after");
  if (text.empty()) return std::nullopt;
  const auto colon = text.find(':');
  v1::EventStop stop;
  stop.set_kind(text.substr(0, colon));
  stop.set_seconds(colon == std::string::npos ? 0.0 : number("--stop-after", text.substr(colon + 1)));
  return stop;
}

inline std::string json_of(const google::protobuf::Message& message) {
  std::string text;
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  (void)google::protobuf::util::MessageToJsonString(message, &text, options);
  return text;
}

inline const char* code_name(grpc::StatusCode code) {
  static const char* names[] = {"OK",         "CANCELLED",      "UNKNOWN",           "INVALID_ARGUMENT",
                                "DEADLINE_EXCEEDED", "NOT_FOUND", "ALREADY_EXISTS",    "PERMISSION_DENIED",
                                "RESOURCE_EXHAUSTED", "FAILED_PRECONDITION", "ABORTED", "OUT_OF_RANGE",
                                "UNIMPLEMENTED", "INTERNAL",     "UNAVAILABLE",        "DATA_LOSS",
                                "UNAUTHENTICATED"};
  return unsigned(code) < sizeof names / sizeof *names ? names[code] : "UNKNOWN";
}

class Remote {
 public:
  Remote(const std::string& command, const Arguments& args) : command_(command), args_(args) {
    const char* env_server = std::getenv("CASCADE_SERVER");
    const char* env_token = std::getenv("CASCADE_TOKEN");
    const std::string address = args.option("--server", env_server ? env_server : "127.0.0.1:50051");
    token_ = args.option("--token", env_token ? env_token : "");
    std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials();
    if (const std::string ca = args.option("--tls-ca"); !ca.empty()) {
      const std::optional<std::string> pem = file_text(ca);
      if (!pem) throw UsageError("cannot read --tls-ca " + ca);
      grpc::SslCredentialsOptions ssl;
      ssl.pem_root_certs = *pem;
      credentials = grpc::SslCredentials(ssl);
    }
    stub_ = v1::SimulationService::NewStub(grpc::CreateChannel(address, credentials));
  }

  void prepare(grpc::ClientContext& context) const {
    if (!token_.empty()) context.AddMetadata("authorization", "Bearer " + token_);
  }
  // Prints a refusal; true when the call succeeded.
  bool ok(const grpc::Status& status) const {
    if (status.ok()) return true;
    std::fprintf(stderr, "cascade %s: %s: %s\n", command_.c_str(), code_name(status.error_code()),
                 status.error_message().c_str());
    return false;
  }
  // The simulation name of positional argument 0 (an ID alone gets its simulations/ prefix).
  std::string simulation() const {
    if (args_.positional.empty()) throw UsageError(command_ + " needs a simulation name (simulations/ID)");
    const std::string& name = args_.positional.front();
    return name.rfind("simulations/", 0) == 0 ? name : "simulations/" + name;
  }
  const std::string& positional(std::size_t k, const char* what) const {
    if (args_.positional.size() <= k) throw UsageError(command_ + " needs " + what);
    return args_.positional[k];
  }

  v1::SimulationService::Stub& stub() { return *stub_; }
  const Arguments& args() const { return args_; }
  const std::string& command() const { return command_; }

 private:
  std::string command_;
  const Arguments& args_;
  std::string token_;
  std::unique_ptr<v1::SimulationService::Stub> stub_;
};

// One unary call with the caller's token; a refusal is printed (Remote::ok). True when it succeeded.
template <typename Request, typename Reply>
bool call(Remote& remote, grpc::Status (v1::SimulationService::Stub::*method)(grpc::ClientContext*, const Request&, Reply*),
          const Request& request, Reply& reply) {
  grpc::ClientContext context;
  remote.prepare(context);
  return remote.ok((remote.stub().*method)(&context, request, &reply));
}

inline const char* state_name(v1::Simulation::State state) {
  return v1::Simulation::State_Name(state).c_str();
}

inline void print_simulation(const v1::Simulation& s) {
  std::printf("%s  %s  %s  t = %.6g s of %.6g, step %llu, %llu particles, stage %s%s%s\n", s.name().c_str(),
              s.case_name().c_str(), state_name(s.state()), s.status().time(), s.end_time(),
              static_cast<unsigned long long>(s.status().step()), static_cast<unsigned long long>(s.particle_count()),
              s.status().stage_name().c_str(), s.failure_reason().empty() ? "" : "  failure: ",
              s.failure_reason().c_str());
}


}  // namespace cascade::cli
