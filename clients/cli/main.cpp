// `cascade`: the command-line client. `cascade run` runs a case headless in this process; the
// other subcommands drive a cascade-server (remote_command.h).
#include <cstdio>
#include <string>
#include <vector>

#include "clients/cli/remote_command.h"
#include "clients/cli/run_command.h"

namespace {

void print_usage(std::FILE* out) {
  std::fputs(
      "usage: cascade <command> [options]\n"
      "\n"
      "in this process:\n"
      "  run CASE.yaml --out DIR [--set key=value]... [--until T] [--threads N] [--precision float|double]\n"
      "      [--replay JOURNAL]\n"
      "        run a case headless; writes fields.h5, fields.xdmf, probes.csv, run.json into DIR\n"
      "        (and snapshots/NAME_NNNNNN.png when the case has output.snapshots);\n"
      "        --replay repeats the forcing changes and stage hand-overs of a server's journal at the same\n"
      "        steps\n"
      "\n"
      "on a server (--server ADDR, default $CASCADE_SERVER or 127.0.0.1:50051; --token T; --tls-ca F; --json):\n"
      "  create CASE.yaml [--set key=value]... [--id ID]\n"
      "  list | get SIM | start SIM | pause SIM | resume SIM | delete SIM\n"
      "  step SIM N | run-until SIM T [--stop-after KIND[:S]]   (S seconds after the first cascade event KIND)\n"
      "  set SIM KEY=VALUE... [--at T]     rainfall.intensity, ponding.p_max, ponding.p_min (none: no limit),\n"
      "        rainfall.factor=F (the case's rain, series or constant, times F), rainfall.region=X0,Z0,X1,Z1\n"
      "        (3D: X0,Y0,Z0,X1,Y1,Z1; none: everywhere)\n"
      "  advance-stage SIM [--reason TEXT]   the hand-over to the case's next stage (ScenarioSpec.stages)\n"
      "  watch SIM [--interval S]\n"
      "  snapshot SIM [SNAPSHOT OPTIONS] --out FILE.png     one PNG, rendered on the server\n"
      "  watch SIM --frames DIR [--every-sim S | --every-wall S] [--count N] [SNAPSHOT OPTIONS]\n"
      "        the stream of PNGs as DIR/frame_NNNNNN.png (default every 1 s of wall time)\n"
      "      SNAPSHOT OPTIONS (docs/rendering.md): --field F --phase water|soil|boundary|all --translucent P\n"
      "        --colour-map viridis|cool_warm --min V --max V --camera side|orbit|look_at --azimuth D\n"
      "        --elevation D --zoom Z --fov D --eye X,Y,Z --target X,Y,Z --width W --height H --background R,G,B\n"
      "  query SIM FIELD... [--phase water|soil|boundary] [--box X0,Y0,Z0,X1,Y1,Z1] [--stride N] --out F.h5|F.csv\n"
      "  probes SIM [--since T] | events SIM [--since T]\n"
      "  checkpoint SIM | checkpoints SIM | restore SIM CHECKPOINT   (ckpt-NNNN or its full name)\n"      "  fork SIM [KEY=VALUE]... [--id ID]   a what-if branch with SIM's state at its next step boundary,\n"
      "        paused there, with the forcing changes of `set`; SIM goes on as it was\n"
      "  ensemble SIM (--rain-factors F,F,... | --hyetograph FILE...) [--time-unit U] [--intensity-unit U]\n"
      "      [--until T] [--stop-after KIND[:S]] [--out FILE.csv]   forks one branch per factor or hyetograph,\n"
      "        runs them side by side and tabulates each branch's events (ponding, landslide onset, impact,\n"
      "        wave at each gauge, overtopping)\n"
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
  if (cascade::cli::is_remote_command(command)) return cascade::cli::remote_command(command, args);
  if (command == "help" || command == "--help" || command == "-h") {
    print_usage(stdout);
    return 0;
  }
  std::fprintf(stderr, "cascade: unknown command '%s'\n", command.c_str());
  print_usage(stderr);
  return 2;
}
