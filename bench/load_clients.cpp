// 32 concurrent gRPC clients against one running simulation, for bench/server_clients.py
// (issue 14, item 10): 8 GetSimulation loops, 8 ListProbes loops, 8 WatchSimulation streams
// (0.05 s), 4 QueryFields loops (pore pressure and velocity of the soil) and 4 RenderSnapshot
// loops (pore pressure of the soil, 320 × 180), each a thread with a channel of its own, back to
// back. The Python clients of that bench spend most of their time in the interpreter and share a
// core with the server's handlers, so that their latency measured mostly themselves; these are
// the same requests from a client whose own cost is small.
//
// Protocol with the bench: every client connects (one GetSimulation), then "ready" is printed;
// the load starts when a line arrives on stdin and lasts --seconds; then one line of JSON:
// {"requests": {kind: n}, "errors": [...], "get_latencies_ms": [...]}.
//
// usage: load_clients --address HOST:PORT --name SIMULATION --seconds S
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cascade/v1/simulation.grpc.pb.h"

namespace {

namespace v1 = cascade::v1;
using Clock = std::chrono::steady_clock;

enum class Kind { get, probes, watch, query, snapshot };
const char* kind_name(Kind k) {
  switch (k) {
    case Kind::get: return "get";
    case Kind::probes: return "probes";
    case Kind::watch: return "watch";
    case Kind::query: return "query";
    case Kind::snapshot: return "snapshot";
  }
  return "?";
}

struct Outcome {
  Kind kind;
  long requests = 0;
  std::vector<std::string> errors;
  std::vector<double> get_latencies_ms;
};

// Start line shared by the clients: they wait until the bench says go.
struct Gate {
  std::mutex mutex;
  std::condition_variable changed;
  int connected = 0;
  bool open = false;
};

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += (c == '\n' ? ' ' : c);
  }
  return out + "\"";
}

void client(Kind kind, const std::string& address, const std::string& name, Gate& gate, std::atomic<bool>& stop,
            grpc::ClientContext& watch_context, Outcome& outcome) {
  // A channel of its own: a distinct argument keeps gRPC from sharing one connection between them.
  grpc::ChannelArguments arguments;
  arguments.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  auto stub = v1::SimulationService::NewStub(
      grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), arguments));
  v1::GetSimulationRequest get;
  get.set_name(name);
  {
    grpc::ClientContext context;
    v1::Simulation reply;
    const grpc::Status status = stub->GetSimulation(&context, get, &reply);
    if (!status.ok()) outcome.errors.push_back(std::string("connect: ") + status.error_message());
  }
  {
    std::unique_lock lock(gate.mutex);
    ++gate.connected;
    gate.changed.notify_all();
    gate.changed.wait(lock, [&] { return gate.open; });
  }
  const auto record = [&](const grpc::Status& status) {
    if (status.ok()) {
      ++outcome.requests;
    } else {
      outcome.errors.push_back(std::string(kind_name(kind)) + ": " + std::to_string(int(status.error_code())) + " " +
                               status.error_message());
    }
  };
  if (kind == Kind::watch) {  // the stream ends when main() cancels its context
    v1::WatchSimulationRequest request;
    request.set_name(name);
    request.set_interval_seconds(0.05);
    auto reader = stub->WatchSimulation(&watch_context, request);
    v1::WatchSimulationResponse update;
    while (reader->Read(&update)) ++outcome.requests;
    const grpc::Status status = reader->Finish();
    if (!status.ok() && !stop)
      outcome.errors.push_back("watch: " + std::to_string(int(status.error_code())) + " " + status.error_message());
    return;
  }
  while (!stop) {
    grpc::ClientContext context;
    if (kind == Kind::get) {
      v1::Simulation reply;
      const auto start = Clock::now();
      const grpc::Status status = stub->GetSimulation(&context, get, &reply);
      outcome.get_latencies_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
      record(status);
    } else if (kind == Kind::probes) {
      v1::ListProbesRequest request;
      request.set_name(name);
      request.set_since_time(-std::numeric_limits<double>::infinity());
      v1::ListProbesResponse reply;
      record(stub->ListProbes(&context, request, &reply));
    } else if (kind == Kind::query) {
      v1::QueryFieldsRequest request;
      request.set_name(name);
      request.add_fields("pore_pressure");
      request.add_fields("velocity");
      request.set_phase("soil");
      auto reader = stub->QueryFields(&context, request);
      v1::FieldChunk chunk;
      while (reader->Read(&chunk)) {
      }
      record(reader->Finish());
    } else {
      v1::RenderSnapshotRequest request;
      request.set_name(name);
      request.mutable_snapshot()->set_field("pore_pressure");
      request.mutable_snapshot()->set_phase("soil");
      request.mutable_snapshot()->set_width(320);
      request.mutable_snapshot()->set_height(180);
      v1::SnapshotImage reply;
      record(stub->RenderSnapshot(&context, request, &reply));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string address, name;
  double seconds = 60;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--address") address = argv[i + 1];
    else if (key == "--name") name = argv[i + 1];
    else if (key == "--seconds") seconds = std::atof(argv[i + 1]);
  }
  if (address.empty() || name.empty() || !(seconds > 0)) {
    std::fprintf(stderr, "usage: load_clients --address HOST:PORT --name SIMULATION --seconds S\n");
    return 2;
  }
  std::vector<Kind> kinds;
  for (auto [kind, n] : {std::pair{Kind::get, 8}, {Kind::probes, 8}, {Kind::watch, 8}, {Kind::query, 4},
                         {Kind::snapshot, 4}})
    kinds.insert(kinds.end(), n, kind);

  Gate gate;
  std::atomic<bool> stop{false};
  std::vector<Outcome> outcomes(kinds.size());
  // The watch streams' contexts live here, so that main() can cancel them.
  std::vector<grpc::ClientContext> watch_contexts(kinds.size());
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    outcomes[k].kind = kinds[k];
    threads.emplace_back(client, kinds[k], address, name, std::ref(gate), std::ref(stop), std::ref(watch_contexts[k]),
                         std::ref(outcomes[k]));
  }
  {
    std::unique_lock lock(gate.mutex);
    gate.changed.wait(lock, [&] { return gate.connected == int(kinds.size()); });
  }
  std::printf("ready\n");
  std::fflush(stdout);
  std::string line;
  std::getline(std::cin, line);
  {
    std::lock_guard lock(gate.mutex);
    gate.open = true;
  }
  gate.changed.notify_all();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  stop = true;
  for (std::size_t k = 0; k < kinds.size(); ++k)
    if (kinds[k] == Kind::watch) watch_contexts[k].TryCancel();
  for (auto& t : threads) t.join();

  std::string requests, errors, latencies;
  for (Kind kind : {Kind::get, Kind::probes, Kind::watch, Kind::query, Kind::snapshot}) {
    long n = 0;
    for (const auto& o : outcomes)
      if (o.kind == kind) n += o.requests;
    requests += std::string(requests.empty() ? "" : ", ") + "\"" + kind_name(kind) + "\": " + std::to_string(n);
  }
  for (const auto& o : outcomes) {
    for (const auto& e : o.errors) errors += std::string(errors.empty() ? "" : ", ") + json_string(e);
    for (double ms : o.get_latencies_ms) {
      char value[32];
      std::snprintf(value, sizeof value, "%.4f", ms);
      latencies += std::string(latencies.empty() ? "" : ", ") + value;
    }
  }
  std::printf("{\"requests\": {%s}, \"errors\": [%s], \"get_latencies_ms\": [%s]}\n", requests.c_str(), errors.c_str(),
              latencies.c_str());
  return 0;
}
