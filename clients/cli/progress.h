// Progress of a headless run: a one-line bar on a terminal, plain log lines otherwise.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>

namespace cascade::cli {

class Progress {
 public:
  Progress(double end_time, std::FILE* out);
  // Called after every step; draws at most a few times a second.
  void update(double sim_time, std::uint64_t steps, double dt);
  void finish(double sim_time, std::uint64_t steps, double dt);

 private:
  void draw(double sim_time, std::uint64_t steps, double dt, bool final_line);

  double end_time_;
  std::FILE* out_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  double interval_seconds_;
};

}  // namespace cascade::cli
