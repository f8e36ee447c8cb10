// `cascade run CASE.yaml --out DIR [--set k=v]... [--until T] [--threads N] [--precision P]
// [--replay JOURNAL]`:
// runs a case headless in this process and writes its outputs (docs/output.md).
#pragma once

#include <string>
#include <vector>

namespace cascade::cli {

// Returns the process exit code: 0 only when the run reached its end time.
int run_command(const std::vector<std::string>& args);

}  // namespace cascade::cli
