// Linked into every validation test program: its OpenMP team takes the cores that other processes
// leave free when it starts, measured over 0.3 s (server/core/free_cores.h), as `cascade run` and
// the server do. A validation run at a team of all cores beside another busy process was many times
// slower than at one thread (docs/performance.md, "Sharing the cores").
#include <omp.h>

#include <chrono>
#include <thread>

#include "server/core/free_cores.h"

namespace {

const int team_size = [] {
  cascade::FreeCores free_cores;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const int threads = free_cores.update(std::chrono::milliseconds(250));
  omp_set_num_threads(threads);
  return threads;
}();

}  // namespace
