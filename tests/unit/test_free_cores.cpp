// FreeCores (server/core/free_cores.h): a process that keeps a core busy takes it from the cores
// this process may size its OpenMP teams to; this process's own threads do not count against it.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "server/core/free_cores.h"

namespace cascade {
namespace {

TEST(FreeCores, ABusyProcessTakesACore) {
  FreeCores free_cores;
  ASSERT_GE(free_cores.cores(), 1);
  const pid_t busy = fork();
  ASSERT_GE(busy, 0);
  if (busy == 0) {
    for (volatile unsigned long k = 0;; ++k) {
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const int free_now = free_cores.update(std::chrono::seconds(1));
  kill(busy, SIGKILL);
  waitpid(busy, nullptr, 0);
  // Other tests may load the machine too: the busy process makes it at most one fewer.
  EXPECT_LE(free_now, std::max(1, free_cores.cores() - 1));
  EXPECT_GE(free_now, 1);
}

TEST(FreeCores, MeasuresOnlyOnceAnInterval) {
  FreeCores free_cores;
  EXPECT_EQ(free_cores.update(std::chrono::hours(1)), free_cores.cores());
}

}  // namespace
}  // namespace cascade
