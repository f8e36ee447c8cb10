#include "clients/cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace cascade::cli {

Progress::Progress(double end_time, std::FILE* out)
    : end_time_(end_time),
      out_(out),
      terminal_(isatty(fileno(out)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_),
      interval_seconds_(terminal_ ? 0.25 : 10.0) {}

void Progress::update(double sim_time, std::uint64_t steps, double dt) {
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_draw_).count() < interval_seconds_) return;
  last_draw_ = now;
  draw(sim_time, steps, dt, false);
}

void Progress::finish(double sim_time, std::uint64_t steps, double dt) { draw(sim_time, steps, dt, true); }

void Progress::draw(double sim_time, std::uint64_t steps, double dt, bool final_line) {
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fraction = std::clamp(sim_time / end_time_, 0.0, 1.0);
  const double steps_per_second = wall > 0 ? double(steps) / wall : 0.0;
  const double eta = fraction > 0 ? wall * (1.0 - fraction) / fraction : 0.0;
  const int eta_s = int(std::lround(eta));
  char eta_text[32];
  std::snprintf(eta_text, sizeof eta_text, "%02d:%02d:%02d", eta_s / 3600, (eta_s / 60) % 60, eta_s % 60);
  if (terminal_) {
    constexpr int width = 30;
    const int filled = int(fraction * width);
    std::string bar(std::size_t(filled), '#');
    bar.resize(width, '.');
    std::fprintf(out_, "\r[%s] %5.1f%%  t = %.4f / %.4f s  step %llu  %.1f steps/s  ETA %s ", bar.c_str(),
                 100.0 * fraction, sim_time, end_time_, static_cast<unsigned long long>(steps), steps_per_second,
                 eta_text);
    if (final_line) std::fputc('\n', out_);
  } else {
    std::fprintf(out_, "progress: t = %.6f / %.6f s (%.1f%%), step %llu, dt = %.3e s, %.1f steps/s, ETA %s\n",
                 sim_time, end_time_, 100.0 * fraction, static_cast<unsigned long long>(steps), dt,
                 steps_per_second, eta_text);
  }
  std::fflush(out_);
}

}  // namespace cascade::cli
