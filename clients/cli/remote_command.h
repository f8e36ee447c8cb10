// `cascade SUBCOMMAND ... --server ADDR [--token T] [--tls-ca F] [--json]`: drives a cascade-server.
// Subcommands that act on a simulation take its name (simulations/ID, or just ID) first:
//   create CASE.yaml [--set k=v]... [--id ID]     list
//   get SIM   start SIM   pause SIM   resume SIM   delete SIM
//   step SIM N        run-until SIM T
//   set SIM KEY=VALUE... [--at T]   (rainfall.intensity, rainfall.factor, rainfall.region=X0,Z0,X1,Z1 in 2D or
//                                    X0,Y0,Z0,X1,Y1,Z1 in 3D, ponding.p_max, ponding.p_min;
//                                    region=none, p_min=none: unset)
//   watch SIM [--interval S]        (a progress line per status, events as they come)
//   query SIM FIELD... [--phase water|soil|boundary] [--box X0,Y0,Z0,X1,Y1,Z1] [--stride N] --out F.h5|F.csv
//   probes SIM [--since T]          events SIM [--since T]
//   checkpoint SIM   checkpoints SIM   restore SIM CHECKPOINT
//   fork SIM [KEY=VALUE]... [--id ID]   (a what-if branch: the forcing keys of set)
//   ensemble SIM ...                (ensemble_command.h)
// --json prints the reply as protobuf JSON (one object per line for watch). The server defaults to
// $CASCADE_SERVER or 127.0.0.1:50051, the token to $CASCADE_TOKEN.
#pragma once

#include <string>
#include <vector>

namespace cascade::cli {

bool is_remote_command(const std::string& command);

// Returns the exit code: 0 done, 1 the server refused or failed (its code and message on stderr),
// 2 a usage error or a bad case file (create loads the case here, hyetograph included, and sends
// the spec).
int remote_command(const std::string& command, const std::vector<std::string>& args);

}  // namespace cascade::cli
