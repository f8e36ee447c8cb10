#include "server/app/server_options.h"

#include <cmath>
#include <stdexcept>

namespace cascade::app {

namespace {

double whole_number(const std::string& option, const std::string& text, double lo, double hi) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !(v >= lo && v <= hi) || v != std::floor(v))
    throw std::invalid_argument(option + " needs a whole number from " + std::to_string(std::int64_t(lo)) + " to " +
                                std::to_string(std::int64_t(hi)) + ", got '" + text + "'");
  return v;
}

}  // namespace

bool is_loopback(const std::string& listen_address) {
  const auto colon = listen_address.rfind(':');
  const std::string host = listen_address.substr(0, colon);
  return host == "localhost" || host == "[::1]" || host.rfind("127.", 0) == 0;
}

ServerOptions parse_server_options(const std::vector<std::string>& args) {
  ServerOptions o;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    auto value = [&]() -> const std::string& {
      if (k + 1 >= args.size()) throw std::invalid_argument(a + " needs a value");
      return args[++k];
    };
    if (a == "--listen") o.listen = value();
    else if (a == "--data-dir") o.data_dir = value();
    else if (a == "--device") {
      const std::string& d = value();
      if (d == "cpu") o.device = Device::cpu;
      else if (d == "cuda") o.device = Device::cuda;
      else throw std::invalid_argument("--device must be cpu or cuda, not '" + d + "'");
    } else if (a == "--threads") o.threads = int(whole_number(a, value(), 1, 1024));
    else if (a == "--tls-cert") o.tls_cert = value();
    else if (a == "--tls-key") o.tls_key = value();
    else if (a == "--tokens") o.tokens = value();
    else if (a == "--max-particles") o.max_particles = std::size_t(whole_number(a, value(), 1, 5e7));
    else if (a == "--max-simulations") o.max_simulations = std::size_t(whole_number(a, value(), 1, 1024));
    else if (a == "--insecure") o.insecure = true;
    else throw std::invalid_argument("unknown option '" + a + "'");
  }
  if (o.data_dir.empty()) throw std::invalid_argument("--data-dir DIR is required");
  if (o.listen.rfind(':') == std::string::npos) throw std::invalid_argument("--listen needs HOST:PORT, got '" + o.listen + "'");
  if (o.tls_cert.empty() != o.tls_key.empty()) throw std::invalid_argument("--tls-cert and --tls-key go together");
  if (!is_loopback(o.listen) && !o.insecure && (o.tls_cert.empty() || o.tokens.empty()))
    throw std::invalid_argument("--listen " + o.listen +
                                " is not a loopback address: it needs --tls-cert, --tls-key and --tokens (or --insecure)");
  return o;
}

}  // namespace cascade::app
