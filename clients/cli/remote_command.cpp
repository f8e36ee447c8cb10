#include "clients/cli/remote_command.h"

#include "clients/cli/ensemble_command.h"
#include "clients/cli/remote.h"

#include <google/protobuf/util/json_util.h>
#include <grpcpp/grpcpp.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "cascade/v1/simulation.grpc.pb.h"
#include "server/io/hdf5_writer.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/file_text.h"

namespace cascade::cli {

namespace {

// A unary call whose reply is a Simulation.
template <typename Request>
int simulation_call(Remote& remote, Request request,
                    grpc::Status (v1::SimulationService::Stub::*method)(grpc::ClientContext*, const Request&, v1::Simulation*)) {
  v1::Simulation reply;
  if (!call(remote, method, request, reply)) return 1;
  if (remote.args().json) std::puts(json_of(reply).c_str());
  else print_simulation(reply);
  return 0;
}

// The case is loaded here, as `cascade run` loads it, and sent as a spec: its hyetograph file (and
// any other file it names) is on this machine, and the server reads no files that a request names.
int create(Remote& remote) {
  v1::CreateSimulationRequest request;
  std::vector<CaseOverride> overrides;
  for (const auto& o : remote.args().all("--set")) overrides.push_back(parse_override(o));
  *request.mutable_spec() = load_case_file(remote.positional(0, "a case file"), overrides);
  request.set_simulation_id(remote.args().option("--id"));
  grpc::ClientContext context;
  remote.prepare(context);
  v1::Simulation reply;
  if (!remote.ok(remote.stub().CreateSimulation(&context, request, &reply))) return 1;
  if (remote.args().json) std::puts(json_of(reply).c_str());
  else print_simulation(reply);
  return 0;
}

int list(Remote& remote) {
  grpc::ClientContext context;
  remote.prepare(context);
  v1::ListSimulationsResponse reply;
  if (!remote.ok(remote.stub().ListSimulations(&context, {}, &reply))) return 1;
  if (remote.args().json) std::puts(json_of(reply).c_str());
  else
    for (const auto& s : reply.simulations()) print_simulation(s);
  return 0;
}

int set_forcing(Remote& remote) {
  v1::UpdateForcingRequest request;
  request.set_name(remote.simulation());
  if (remote.args().positional.size() < 2) throw UsageError("set needs KEY=VALUE " + kSteerable);
  for (std::size_t k = 1; k < remote.args().positional.size(); ++k)
    add_forcing("set", remote.args().positional[k], *request.mutable_forcing(), *request.mutable_update_mask());
  if (const std::string at = remote.args().option("--at"); !at.empty()) request.set_effective_time(number("--at", at));
  grpc::ClientContext context;
  remote.prepare(context);
  v1::UpdateForcingResponse reply;
  if (!remote.ok(remote.stub().UpdateForcing(&context, request, &reply))) return 1;
  if (remote.args().json) std::puts(json_of(reply).c_str());
  else
    std::printf("%s: from step %llu (t = %.9g s): %s\n", request.name().c_str(),
                static_cast<unsigned long long>(reply.effective_step()), reply.effective_time(),
                reply.forcing().ShortDebugString().c_str());
  return 0;
}

// fork SIM [KEY=VALUE]... [--id ID]: a what-if branch from the parent's next step boundary.
int fork(Remote& remote) {
  v1::ForkSimulationRequest request;
  request.set_name(remote.simulation());
  request.set_simulation_id(remote.args().option("--id"));
  for (std::size_t k = 1; k < remote.args().positional.size(); ++k)
    add_forcing("fork", remote.args().positional[k], *request.mutable_forcing(), *request.mutable_update_mask());
  return simulation_call(remote, request, &v1::SimulationService::Stub::ForkSimulation);
}

int watch_frames(Remote& remote);

int watch(Remote& remote) {
  if (!remote.args().option("--frames").empty()) return watch_frames(remote);
  v1::WatchSimulationRequest request;
  request.set_name(remote.simulation());
  if (const std::string s = remote.args().option("--interval"); !s.empty()) request.set_interval_seconds(number("--interval", s));
  grpc::ClientContext context;
  remote.prepare(context);
  auto reader = remote.stub().WatchSimulation(&context, request);
  v1::WatchSimulationResponse update;
  while (reader->Read(&update)) {
    if (remote.args().json) {
      std::puts(json_of(update).c_str());
    } else if (update.has_status()) {
      const auto& s = update.status();
      std::printf("%s  t = %.6g s  step %llu  dt = %.3g s  %.1f steps/s  KE = %.4g J  max soil speed %.3g m/s  stage %s",
                  state_name(s.state()), s.time(), static_cast<unsigned long long>(s.step()), s.dt(),
                  s.steps_per_second(), s.kinetic_energy(), s.max_soil_speed(), s.stage_name().c_str());
      // The pore water's account (docs/api.md), for a case with soil.
      if (s.has_pore_water())
        std::printf("  pore water in: rain %.4g, walls %.4g, surface %.4g", s.pore_water().rain(), s.pore_water().walls(),
                    s.pore_water().surface());
      std::printf("\n");
    } else {
      const auto& e = update.event();
      std::printf("event  t = %.6g s  step %llu  %s: %s (%s)\n", e.time(), static_cast<unsigned long long>(e.step()),
                  e.kind().c_str(), e.message().c_str(), e.caller().c_str());
    }
    std::fflush(stdout);
  }
  return remote.ok(reader->Finish()) ? 0 : 1;
}

// The chunks of a query as one frame.
FieldFrame assemble(const std::vector<v1::FieldChunk>& chunks) {
  FieldFrame frame;
  for (const auto& chunk : chunks) {
    frame.time = chunk.time();
    frame.step = chunk.step();
    frame.dimensions = int(chunk.dimensions());
    frame.id.insert(frame.id.end(), chunk.id().begin(), chunk.id().end());
    frame.position.insert(frame.position.end(), chunk.position().begin(), chunk.position().end());
    for (auto p : chunk.phase()) frame.phase.push_back(std::uint8_t(p));
    for (int k = 0; k < chunk.fields_size(); ++k) {
      const auto& values = chunk.fields(k);
      if (frame.fields.size() <= std::size_t(k))
        frame.fields.push_back({values.name(), values.units(), int(values.components()), {}});
      auto& field = frame.fields[std::size_t(k)].values;
      field.insert(field.end(), values.values().begin(), values.values().end());
    }
  }
  return frame;
}

void write_csv(const FieldFrame& frame, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << "id,phase,x,y,z";
  for (const auto& f : frame.fields)
    for (int c = 0; c < f.components; ++c) out << ',' << f.name << (f.components > 1 ? "_" + std::to_string(c) : "");
  out << '\n';
  char text[32];
  auto put = [&](double v) {
    std::snprintf(text, sizeof text, ",%.17g", v);
    out << text;
  };
  for (std::size_t i = 0; i < frame.size(); ++i) {
    out << frame.id[i] << ',' << int(frame.phase[i]);
    for (int a = 0; a < 3; ++a) put(frame.position[3 * i + a]);
    for (const auto& f : frame.fields)
      for (int c = 0; c < f.components; ++c) put(f.values[i * std::size_t(f.components) + c]);
    out << '\n';
  }
}

int query(Remote& remote) {
  v1::QueryFieldsRequest request;
  request.set_name(remote.simulation());
  for (std::size_t k = 1; k < remote.args().positional.size(); ++k) request.add_fields(remote.args().positional[k]);
  request.set_phase(remote.args().option("--phase"));
  if (const std::string box = remote.args().option("--box"); !box.empty()) {
    const auto v = numbers("--box", box, 6, "X0,Y0,Z0,X1,Y1,Z1");
    for (int a = 0; a < 3; ++a) {
      request.mutable_box()->add_min(v[std::size_t(a)]);
      request.mutable_box()->add_max(v[std::size_t(a) + 3]);
    }
  }
  if (const std::string s = remote.args().option("--stride"); !s.empty()) {
    const double stride = number("--stride", s);
    if (!(stride >= 0 && stride <= 4e9 && stride == std::floor(stride))) throw UsageError("--stride needs a whole number");
    request.set_stride(std::uint32_t(stride));
  }
  const std::string out = remote.args().option("--out");
  const bool csv = out.size() > 4 && out.substr(out.size() - 4) == ".csv";
  const bool h5 = out.size() > 3 && out.substr(out.size() - 3) == ".h5";
  if (!csv && !h5) throw UsageError("query needs --out FILE.h5 or FILE.csv");
  grpc::ClientContext context;
  remote.prepare(context);
  auto reader = remote.stub().QueryFields(&context, request);
  std::vector<v1::FieldChunk> chunks;
  for (v1::FieldChunk chunk; reader->Read(&chunk);) chunks.push_back(std::move(chunk));
  if (!remote.ok(reader->Finish())) return 1;
  const FieldFrame frame = assemble(chunks);
  if (csv) write_csv(frame, out);
  else Hdf5FieldWriter(out).write(frame);
  if (remote.args().json)
    std::printf("{\"file\": \"%s\", \"particles\": %zu, \"time\": %.17g, \"step\": %llu, \"chunks\": %zu}\n", out.c_str(),
                frame.size(), frame.time, static_cast<unsigned long long>(frame.step), chunks.size());
  else
    std::printf("%s: %zu particles at t = %.9g s (step %llu) in %s\n", request.name().c_str(), frame.size(), frame.time,
                static_cast<unsigned long long>(frame.step), out.c_str());
  return 0;
}

int probes(Remote& remote) {
  v1::ListProbesRequest request;
  request.set_name(remote.simulation());
  if (const std::string s = remote.args().option("--since"); !s.empty()) request.set_since_time(number("--since", s));
  else request.set_since_time(-INFINITY);
  grpc::ClientContext context;
  remote.prepare(context);
  v1::ListProbesResponse reply;
  if (!remote.ok(remote.stub().ListProbes(&context, request, &reply))) return 1;
  if (remote.args().json) {
    std::puts(json_of(reply).c_str());
    return 0;
  }
  std::printf("time");
  for (const auto& name : reply.probe_names()) std::printf(",%s", name.c_str());
  std::printf("\n");
  for (const auto& sample : reply.samples()) {
    std::printf("%.17g", sample.time());
    for (double v : sample.values()) std::printf(",%.17g", v);
    std::printf("\n");
  }
  return 0;
}

int events(Remote& remote) {
  v1::ListEventsRequest request;
  request.set_name(remote.simulation());
  if (const std::string s = remote.args().option("--since"); !s.empty()) request.set_since_time(number("--since", s));
  grpc::ClientContext context;
  remote.prepare(context);
  v1::ListEventsResponse reply;
  if (!remote.ok(remote.stub().ListEvents(&context, request, &reply))) return 1;
  if (remote.args().json) std::puts(json_of(reply).c_str());
  else
    for (const auto& e : reply.events())
      std::printf("t = %.9g s  step %llu  %s: %s (%s)\n", e.time(), static_cast<unsigned long long>(e.step()),
                  e.kind().c_str(), e.message().c_str(), e.caller().c_str());
  return 0;
}

int remove(Remote& remote) {
  v1::DeleteSimulationRequest request;
  request.set_name(remote.simulation());
  grpc::ClientContext context;
  remote.prepare(context);
  google::protobuf::Empty reply;
  if (!remote.ok(remote.stub().DeleteSimulation(&context, request, &reply))) return 1;
  if (remote.args().json) std::printf("{\"deleted\": \"%s\"}\n", request.name().c_str());
  else std::printf("deleted %s\n", request.name().c_str());
  return 0;
}

// What a snapshot shows, from the options; the server checks the values and names the field.
v1::Snapshot snapshot_of(const Arguments& args) {
  v1::Snapshot s;
  s.set_field(args.option("--field"));
  s.set_phase(args.option("--phase"));
  for (const auto& phase : args.all("--translucent")) s.add_translucent(phase);
  s.set_colour_map(args.option("--colour-map"));
  if (const auto v = args.option("--min"); !v.empty()) s.set_min(number("--min", v));
  if (const auto v = args.option("--max"); !v.empty()) s.set_max(number("--max", v));
  s.set_camera(args.option("--camera"));
  auto* orbit = s.mutable_orbit();
  if (const auto v = args.option("--azimuth"); !v.empty()) orbit->set_azimuth(number("--azimuth", v));
  if (const auto v = args.option("--elevation"); !v.empty()) orbit->set_elevation(number("--elevation", v));
  if (const auto v = args.option("--zoom"); !v.empty()) orbit->set_zoom(number("--zoom", v));
  const std::string eye = args.option("--eye"), target = args.option("--target"), fov = args.option("--fov");
  if (!eye.empty() || !target.empty()) {
    for (double c : numbers("--eye", eye, 3, "X,Y,Z")) s.mutable_look_at()->add_eye(c);
    for (double c : numbers("--target", target, 3, "X,Y,Z")) s.mutable_look_at()->add_target(c);
    if (!fov.empty()) s.mutable_look_at()->set_fov(number("--fov", fov));
  } else if (!fov.empty()) {
    orbit->set_fov(number("--fov", fov));
  }
  if (orbit->ByteSizeLong() == 0) s.clear_orbit();  // only the orbit camera may have one
  if (const auto v = args.option("--width"); !v.empty()) s.set_width(int(number("--width", v)));
  if (const auto v = args.option("--height"); !v.empty()) s.set_height(int(number("--height", v)));
  if (const auto v = args.option("--background"); !v.empty())
    for (double c : numbers("--background", v, 3, "R,G,B in [0, 1]")) s.add_background(c);
  return s;
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  if (!out.write(bytes.data(), std::streamsize(bytes.size()))) throw std::runtime_error("cannot write " + path);
}

void print_image(const v1::SnapshotImage& image, const std::string& path) {
  std::printf("%s: t = %.9g s  step %llu  %s [%.6g, %.6g] %s  %ux%u  %llu particles\n", path.c_str(), image.time(),
              static_cast<unsigned long long>(image.step()), image.field().c_str(), image.range_min(),
              image.range_max(), image.units().c_str(), image.width(), image.height(),
              static_cast<unsigned long long>(image.drawn_particles()));
  std::fflush(stdout);
}

// The image's metadata as JSON, without the PNG bytes.
std::string metadata_json(v1::SnapshotImage image, const std::string& path) {
  image.clear_png();
  std::string text = json_of(image);
  return "{\"file\": \"" + path + "\", " + text.substr(1);
}

int snapshot(Remote& remote) {
  v1::RenderSnapshotRequest request;
  request.set_name(remote.simulation());
  *request.mutable_snapshot() = snapshot_of(remote.args());
  const std::string out = remote.args().option("--out");
  if (out.empty()) throw UsageError("snapshot needs --out FILE.png");
  grpc::ClientContext context;
  remote.prepare(context);
  v1::SnapshotImage image;
  if (!remote.ok(remote.stub().RenderSnapshot(&context, request, &image))) return 1;
  write_file(out, image.png());
  if (remote.args().json) std::puts(metadata_json(image, out).c_str());
  else print_image(image, out);
  return 0;
}

// watch SIM --frames DIR: the stream's PNGs as DIR/frame_NNNNNN.png, numbered from 0.
int watch_frames(Remote& remote) {
  v1::StreamSnapshotsRequest request;
  request.set_name(remote.simulation());
  *request.mutable_snapshot() = snapshot_of(remote.args());
  const std::string every_sim = remote.args().option("--every-sim"), every_wall = remote.args().option("--every-wall");
  if (!every_sim.empty()) request.set_every_simulated_seconds(number("--every-sim", every_sim));
  else request.set_every_wall_seconds(every_wall.empty() ? 1.0 : number("--every-wall", every_wall));
  const double count = remote.args().option("--count").empty() ? 0 : number("--count", remote.args().option("--count"));
  const std::filesystem::path dir = remote.args().option("--frames");
  std::filesystem::create_directories(dir);
  grpc::ClientContext context;
  remote.prepare(context);
  auto reader = remote.stub().StreamSnapshots(&context, request);
  int written = 0;
  for (v1::SnapshotImage image; reader->Read(&image);) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", written++);
    const std::string path = (dir / name).string();
    write_file(path, image.png());
    if (remote.args().json) std::puts(metadata_json(image, path).c_str());
    else print_image(image, path);
    if (count > 0 && written >= count) {
      context.TryCancel();  // enough frames: the server sees the client go
      reader->Finish();
      return 0;
    }
  }
  return remote.ok(reader->Finish()) ? 0 : 1;
}

void print_checkpoint(const v1::Checkpoint& c) {
  if (!c.error().empty()) return (void)std::printf("%s  unreadable: %s\n", c.name().c_str(), c.error().c_str());
  std::printf("%s  t = %.9g s, step %llu  %s\n", c.name().c_str(), c.time(), static_cast<unsigned long long>(c.step()),
              c.path().c_str());
}

int checkpoint(Remote& remote) {
  v1::CreateCheckpointRequest request;
  request.set_parent(remote.simulation());
  grpc::ClientContext context;
  remote.prepare(context);
  v1::Checkpoint reply;
  if (!remote.ok(remote.stub().CreateCheckpoint(&context, request, &reply))) return 1;
  if (remote.args().json) std::puts(json_of(reply).c_str());
  else print_checkpoint(reply);
  return 0;
}

int checkpoints(Remote& remote) {
  v1::ListCheckpointsRequest request;
  request.set_parent(remote.simulation());
  grpc::ClientContext context;
  remote.prepare(context);
  v1::ListCheckpointsResponse reply;
  if (!remote.ok(remote.stub().ListCheckpoints(&context, request, &reply))) return 1;
  if (remote.args().json) std::puts(json_of(reply).c_str());
  else
    for (const auto& c : reply.checkpoints()) print_checkpoint(c);
  return 0;
}

template <typename Request>
Request named(const Remote& remote) {
  Request request;
  request.set_name(remote.simulation());
  return request;
}

using Handler = std::function<int(Remote&)>;

const std::map<std::string, Handler>& handlers() {
  using Stub = v1::SimulationService::Stub;
  static const std::map<std::string, Handler> table = {
      {"create", create},
      {"list", list},
      {"get", [](Remote& r) { return simulation_call(r, named<v1::GetSimulationRequest>(r), &Stub::GetSimulation); }},
      {"start", [](Remote& r) { return simulation_call(r, named<v1::StartSimulationRequest>(r), &Stub::StartSimulation); }},
      {"pause", [](Remote& r) { return simulation_call(r, named<v1::PauseSimulationRequest>(r), &Stub::PauseSimulation); }},
      {"resume", [](Remote& r) { return simulation_call(r, named<v1::ResumeSimulationRequest>(r), &Stub::ResumeSimulation); }},
      {"step",
       [](Remote& r) {
         auto request = named<v1::StepSimulationRequest>(r);
         const double n = number("step N", r.positional(1, "a number of steps"));
         if (!(n >= 1 && n <= 1e12 && n == std::floor(n))) throw UsageError("step needs a whole number of steps >= 1");
         request.set_steps(std::uint64_t(n));
         return simulation_call(r, request, &Stub::StepSimulation);
       }},
      {"run-until",
       [](Remote& r) {
         auto request = named<v1::RunSimulationUntilRequest>(r);
         request.set_time(number("run-until T", r.positional(1, "a time in seconds")));
         if (const auto stop = event_stop(r.args())) *request.mutable_stop_after_event() = *stop;
         return simulation_call(r, request, &Stub::RunSimulationUntil);
       }},
      {"set", set_forcing},
      {"advance-stage",
       [](Remote& r) {
         auto request = named<v1::AdvanceStageRequest>(r);
         request.set_reason(r.args().option("--reason"));
         return simulation_call(r, request, &Stub::AdvanceStage);
       }},
      {"watch", watch},
      {"query", query},
      {"snapshot", snapshot},
      {"probes", probes},
      {"events", events},
      {"delete", remove},
      {"checkpoint", checkpoint},
      {"fork", fork},
      {"ensemble", ensemble},
      {"checkpoints", checkpoints},
      {"restore",
       [](Remote& r) {
         // The checkpoint by its id (ckpt-0001) or its full name.
         const std::string& checkpoint = r.positional(1, "a checkpoint (ckpt-NNNN or its full name)");
         v1::RestoreCheckpointRequest request;
         request.set_name(checkpoint.find('/') == std::string::npos ? r.simulation() + "/checkpoints/" + checkpoint
                                                                    : checkpoint);
         return simulation_call(r, request, &Stub::RestoreCheckpoint);
       }},
  };
  return table;
}

}  // namespace

bool is_remote_command(const std::string& command) { return handlers().count(command) > 0; }

int remote_command(const std::string& command, const std::vector<std::string>& args) {
  try {
    const Arguments parsed = parse_arguments(args);
    Remote remote(command, parsed);
    return handlers().at(command)(remote);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "cascade %s: %s\n", command.c_str(), e.what());
    return 2;
  } catch (const CaseError& e) {  // as `cascade run`: a bad case is the caller's mistake
    std::fprintf(stderr, "cascade %s: %s\n", command.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cascade %s: %s\n", command.c_str(), e.what());
    return 1;
  }
}

}  // namespace cascade::cli
