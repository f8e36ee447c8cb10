// cascade-server: the steering server (server/app/server_options.h for its command line).
// SIGTERM or SIGINT: every simulation pauses at its next step boundary, a running or paused one
// writes a checkpoint there, its journal is closed with a `shutdown` entry, open streams end, and
// the process exits 0.
//
// Launched by mpirun as several processes (issue 17), process 0 is the server and every
// session's engine is split over all of them (server/parallel/split_server.h); the others take
// no signal of their own and end when process 0 does.
#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <vector>

#include "server/app/server_options.h"
#include "server/parallel/launched_processes.h"
#include "server/scenario/file_text.h"
#include "server/service/simulation_service.h"
#include "server/service/unparsable_request.h"
#if defined(CASCADE_HAVE_MPI)
#include "server/parallel/mpi_transport.h"
#include "server/parallel/split_server.h"
#endif

namespace {

std::string read_file(const std::filesystem::path& path) {
  if (auto text = cascade::file_text(path)) return *text;
  throw std::runtime_error("cannot read " + path.string());
}

std::shared_ptr<grpc::ServerCredentials> credentials(const cascade::app::ServerOptions& options) {
  if (options.tls_cert.empty()) return grpc::InsecureServerCredentials();
  grpc::SslServerCredentialsOptions ssl;
  ssl.pem_key_cert_pairs.push_back({read_file(options.tls_key), read_file(options.tls_cert)});
  return grpc::SslServerCredentials(ssl);
}

}  // namespace

// Serves until SIGTERM or SIGINT (blocked in every thread: `signals`), then stops the simulations;
// every session and its engine are gone when it returns.
int serve(const cascade::app::ServerOptions& options, cascade::service::ServiceOptions service_options,
          const sigset_t& signals) {
  using namespace cascade;
  if (!app::is_loopback(options.listen) && (options.tls_cert.empty() || options.tokens.empty()))
    std::fprintf(stderr, "cascade-server: WARNING: --insecure: %s is reachable from other machines %s\n",
                 options.listen.c_str(), options.tls_cert.empty() ? "without TLS" : "without tokens");

  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  service::SimulationService simulations(std::move(service_options));
  grpc::ServerBuilder builder;
  int port = 0;
  try {
    builder.AddListeningPort(options.listen, credentials(options), &port);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cascade-server: %s\n", e.what());
    return 2;
  }
  builder.SetMaxReceiveMessageSize(4 << 20);
  builder.RegisterService(&simulations);
  std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> interceptors;
  interceptors.push_back(service::unparsable_request_interceptors());
  builder.experimental().SetInterceptorCreators(std::move(interceptors));
  const std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    std::fprintf(stderr, "cascade-server: cannot listen on %s\n", options.listen.c_str());
    return 1;
  }
  const std::string host = options.listen.substr(0, options.listen.rfind(':'));
  std::fprintf(stderr, "cascade-server: listening on %s:%d, data in %s\n", host.c_str(), port,
               options.data_dir.c_str());

  int signal = 0;
  sigwait(&signals, &signal);
  std::fprintf(stderr, "cascade-server: signal %d: stopping the simulations\n", signal);
  server->GetHealthCheckService()->SetServingStatus(false);
  simulations.shutdown();
  server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  server->Wait();
  return 0;
}

int main(int argc, char** argv) {
  using namespace cascade;
  app::ServerOptions options;
  service::ServiceOptions service_options;
  try {
    options = app::parse_server_options({argv + 1, argv + argc});
    std::filesystem::create_directories(options.data_dir);
    service_options.data_dir = options.data_dir;
    service_options.threads = options.threads;
    service_options.device = options.device;
    service_options.max_particles = options.max_particles;
    service_options.max_simulations = options.max_simulations;
    if (!options.tokens.empty()) service_options.access = service::AccessControl::from_file(options.tokens);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cascade-server: %s\n", e.what());
    return 2;
  }
  // Signals are taken by sigwait (serve), not by a handler: block them before any thread starts
  // so that every thread inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  const int processes = launched_processes();
  if (processes == 1) {
    const int code = serve(options, std::move(service_options), signals);
    if (code == 0) std::fprintf(stderr, "cascade-server: stopped\n");
    return code;
  }
#if defined(CASCADE_HAVE_MPI)
  try {
    MpiSession mpi(&argc, &argv, true);
    int process = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &process);
    if (process != 0) {
      follow_split_engines(service_options.precision, options.device, options.threads);
      return 0;
    }
    SplitEngineLauncher launcher;
    service_options.split_engine = [&launcher](const v1::ScenarioSpec& spec) { return launcher.factory(spec); };
    std::fprintf(stderr, "cascade-server: split over %d processes (mpirun): each simulation's engine spans them all\n",
                 processes);
    const int code = serve(options, std::move(service_options), signals);
    launcher.finish();
    if (code == 0) std::fprintf(stderr, "cascade-server: stopped\n");
    return code;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cascade-server: %s\n", e.what());
    return 1;
  }
#else
  std::fprintf(stderr, "cascade-server: launched as %d processes, but this build has no MPI (configure with "
               "-DCASCADE_MPI=ON)\n", processes);
  return 2;
#endif
}
