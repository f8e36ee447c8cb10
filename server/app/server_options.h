// The command line of cascade-server:
//   cascade-server [--listen HOST:PORT] --data-dir DIR [--device cpu|cuda] [--threads N]
//                  [--tls-cert F --tls-key F] [--tokens F] [--max-particles N]
//                  [--max-simulations N] [--insecure]
// It listens on 127.0.0.1:50051 by default; any other host needs TLS and a token file unless
// --insecure is given (then it warns). Port 0 picks a free port, printed at start.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "server/core/engine.h"

namespace cascade::app {

struct ServerOptions {
  std::string listen = "127.0.0.1:50051";
  std::filesystem::path data_dir;
  Device device = Device::cpu;
  int threads = 0;
  std::filesystem::path tls_cert, tls_key, tokens;
  std::size_t max_particles = 2'000'000;
  std::size_t max_simulations = 8;
  bool insecure = false;
};

// Throws std::invalid_argument with a message naming the option.
ServerOptions parse_server_options(const std::vector<std::string>& args);

// 127.0.0.1 (any 127.x), localhost, [::1].
bool is_loopback(const std::string& listen_address);

}  // namespace cascade::app
