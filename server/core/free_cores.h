// How many OpenMP threads a run may use without outnumbering the cores that other processes leave
// free. OpenMP teams synchronise at the end of every parallel loop (dozens a step): when one of
// their threads shares a core with another busy process, the whole team waits for that thread's
// next time slice at each of them, and a run at 2 threads beside a busy core becomes many times
// slower than at 1 thread (docs/performance.md, "Sharing the cores"). So runs that were not given a
// thread count measure, about once a second, the CPU time that other processes took on the cores
// this process may use (/proc/stat per core, less this process's own time from /proc/self/stat),
// and size their teams to the cores left, shared among the simulations of this process that are
// running (CoreShare).
#pragma once

#include <omp.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>

namespace cascade {

class FreeCores {
 public:
  // At most OMP_NUM_THREADS (OpenMP's default team size) when it is set.
  FreeCores() : cores_(std::min(usable_cores(), omp_get_max_threads())), free_(cores_) { take_sample(last_); }

  int cores() const { return cores_; }

  // Cores that other processes left free over the last measured interval (at least 1); measures
  // anew when `interval` has passed since the last measurement.
  int update(std::chrono::duration<double> interval = std::chrono::seconds(1)) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_.when < interval) return free_;
    Sample sample;
    if (!take_sample(sample)) return free_;
    const double wall_ticks = std::chrono::duration<double>(sample.when - last_.when).count() * ticks_per_second();
    const double others_busy = double(sample.busy_ticks - last_.busy_ticks) - double(sample.own_ticks - last_.own_ticks);
    // Another process counts as holding a core from half of one on: with one of our threads on
    // its core it gets about half, and alone all of it.
    const int busy_cores = int(std::floor(std::max(0.0, others_busy) / wall_ticks + 0.5));
    free_ = std::clamp(cores_ - busy_cores, 1, cores_);
    last_ = sample;
    return free_;
  }

 private:
  struct Sample {
    std::chrono::steady_clock::time_point when;
    unsigned long long busy_ticks = 0;  // user, nice, system, irq, softirq, steal on our cores
    unsigned long long own_ticks = 0;   // this process's user and system time
  };

  static int usable_cores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
    return std::max(1, CPU_COUNT(&set));
  }

  static double ticks_per_second() { return double(sysconf(_SC_CLK_TCK)); }

  // false when /proc is not readable (then the team keeps its size).
  static bool take_sample(Sample& sample) {
    sample.when = std::chrono::steady_clock::now();
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) return false;
    std::ifstream stat("/proc/stat");
    if (!stat) return false;
    sample.busy_ticks = 0;
    std::string line;
    while (std::getline(stat, line)) {
      // "cpuN user nice system idle iowait irq softirq steal ..." (proc(5)); the "cpu " total is skipped.
      if (line.compare(0, 3, "cpu") != 0 || line.size() < 4 || line[3] == ' ') continue;
      std::istringstream fields(line.substr(3));
      int cpu = -1;
      unsigned long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
      fields >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
      if (cpu >= 0 && cpu < CPU_SETSIZE && CPU_ISSET(cpu, &set))
        sample.busy_ticks += user + nice + system + irq + softirq + steal;
    }
    // /proc/self/stat: the command name in parentheses may hold spaces; utime and stime are the
    // 12th and 13th fields after its closing parenthesis (proc(5) fields 14 and 15).
    std::ifstream self("/proc/self/stat");
    std::string text((std::istreambuf_iterator<char>(self)), std::istreambuf_iterator<char>());
    const auto close = text.rfind(')');
    if (close == std::string::npos) return false;
    std::istringstream after(text.substr(close + 1));
    std::string field;
    for (int k = 0; k < 11 && after >> field;) ++k;
    unsigned long long utime = 0, stime = 0;
    if (!(after >> utime >> stime)) return false;
    sample.own_ticks = utime + stime;
    return true;
  }

  int cores_;
  int free_;
  Sample last_;
};

// The cores left free, shared among this process's running simulations (the server runs one
// OpenMP team per simulation; `cascade run` runs one). A simulation holds a Running claim while it
// steps and asks, before each step, how many threads its team may take.
class CoreShare {
 public:
  static CoreShare& of_this_process() {
    static CoreShare share;
    return share;
  }

  class Running {
   public:
    Running() {
      std::lock_guard lock(of_this_process().mutex_);
      ++of_this_process().running_;
    }
    ~Running() {
      std::lock_guard lock(of_this_process().mutex_);
      --of_this_process().running_;
    }
    Running(const Running&) = delete;
    Running& operator=(const Running&) = delete;
  };

  int threads_per_simulation() {
    std::lock_guard lock(mutex_);
    return std::max(1, free_cores_.update() / std::max(1, running_));
  }

 private:
  CoreShare() = default;
  std::mutex mutex_;
  FreeCores free_cores_;
  int running_ = 0;
};

}  // namespace cascade
