// `cascade`: the command-line client. `cascade run` runs a case headless in this process.
#include <cstdio>
#include <string>
#include <vector>

#include "clients/cli/run_command.h"

namespace {

void print_usage(std::FILE* out) {
  std::fputs(
      "usage: cascade <command> [options]\n"
      "\n"
      "commands:\n"
      "  run CASE.yaml --out DIR [--set key=value]... [--until T] [--threads N] [--precision float|double]\n"
      "        run a case headless; writes fields.h5, fields.xdmf, probes.csv, run.json into DIR\n"
      "        (and snapshots/NAME_NNNNNN.png when the case has output.snapshots)\n"
      "  help  this text\n",
      out);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    print_usage(stderr);
    return 2;
  }
  const std::string command = args.front();
  args.erase(args.begin());
  if (command == "run") return cascade::cli::run_command(args);
  if (command == "help" || command == "--help" || command == "-h") {
    print_usage(stdout);
    return 0;
  }
  std::fprintf(stderr, "cascade: unknown command '%s'\n", command.c_str());
  print_usage(stderr);
  return 2;
}
