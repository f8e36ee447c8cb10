#include "server/scenario/cascade_events.h"

#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "server/scenario/number_text.h"

namespace cascade {
namespace {

constexpr std::uint8_t kWater = 0, kSoil = 1;

double speed_of(const FieldFrame::RealField& velocity, std::size_t i) {
  const double* v = &velocity.values[3 * i];
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

std::string at(const FieldFrame& frame, std::size_t i) {
  return "(" + number_text(frame.position[3 * i]) + ", " + number_text(frame.position[3 * i + 1]) + ", " +
         number_text(frame.position[3 * i + 2]) + ") m";
}

}  // namespace

CascadeEventDetector::CascadeEventDetector(const v1::ScenarioSpec& spec, double h,
                                           const std::vector<std::string>& probe_names)
    : events_(spec.events()), dimensions_(spec.dimensions()), dp_(spec.dp()), h_(h), enabled_(spec.has_events()) {
  for (const v1::WaveAtGauge& w : events_.wave_at_gauge())
    for (std::size_t c = 0; c < probe_names.size(); ++c)
      if (probe_names[c] == w.probe())
        gauges_.push_back({w.probe(), int(c), w.rise(), std::numeric_limits<double>::quiet_NaN()});
  for (const v1::Overtopping& o : events_.overtopping()) lines_.push_back({o});
}

std::vector<CascadeEvent> CascadeEventDetector::observe(const FieldFrame& frame, const std::vector<double>& probe_values,
                                                        double ponding_pressure) {
  std::vector<CascadeEvent> fired;
  if (!enabled_) return fired;
  std::string message;
  if (events_.ponding_started() && !ponding_fired_ && ponding(frame, ponding_pressure, message)) {
    ponding_fired_ = true;
    fired.push_back({"ponding_started", message});
  }
  if (events_.has_landslide_onset() && !landslide_fired_ && landslide(frame, message)) {
    landslide_fired_ = true;
    fired.push_back({"landslide_onset", message});
  }
  if (events_.has_water_impact() && !impact_fired_ && impact(frame, message)) {
    impact_fired_ = true;
    fired.push_back({"water_impact", message});
  }
  for (Gauge& g : gauges_) {
    const double value = probe_values[std::size_t(g.column)];
    if (std::isnan(g.first)) g.first = value;  // the still water level
    if (!g.fired && value - g.first > g.rise) {
      g.fired = true;
      fired.push_back({"wave_at_gauge", g.probe + ": elevation " + number_text(value) + " m, " +
                                            number_text(value - g.first) + " m above its first sample " +
                                            number_text(g.first) + " m"});
    }
  }
  for (Line& l : lines_)
    if (!l.fired && overtopped(frame, l.spec, message)) {
      l.fired = true;
      fired.push_back({"overtopping", message});
    }
  return fired;
}

// A free-surface soil particle at p_max: the Eq. 39 switch holds it there once it has reached it.
bool CascadeEventDetector::ponding(const FieldFrame& frame, double ponding_pressure, std::string& message) const {
  const auto* p = frame.find("pore_pressure");
  if (!p || frame.free_surface.size() != frame.size()) return false;
  const double tolerance = 1e-6 * (1.0 + std::fabs(ponding_pressure));
  std::size_t count = 0, first = 0;
  for (std::size_t i = 0; i < frame.size(); ++i)
    if (frame.phase[i] == kSoil && frame.free_surface[i] && p->values[i] >= ponding_pressure - tolerance)
      if (count++ == 0) first = i;
  if (count == 0) return false;
  message = std::to_string(count) + " free-surface soil particle(s) at p_max = " + number_text(ponding_pressure) +
            " Pa, e.g. at " + at(frame, first);
  return true;
}

bool CascadeEventDetector::landslide(const FieldFrame& frame, std::string& message) const {
  const v1::LandslideOnset& l = events_.landslide_onset();
  const auto* kappa = frame.find("plastic_strain");
  const auto* velocity = frame.find("velocity");
  if (!kappa || !velocity) return false;
  const double particle_volume = std::pow(dp_, dimensions_);
  double volume = 0, fastest = 0;
  for (std::size_t i = 0; i < frame.size(); ++i)
    if (frame.phase[i] == kSoil && kappa->values[i] > l.plastic_strain()) {
      const double speed = speed_of(*velocity, i);
      if (speed > l.speed()) {
        volume += particle_volume;
        fastest = std::fmax(fastest, speed);
      }
    }
  if (!(volume > l.volume())) return false;
  message = number_text(volume) + (dimensions_ == 2 ? " m²" : " m³") + " of soil with κ > " +
            number_text(l.plastic_strain()) + " faster than " + number_text(l.speed()) + " m/s (fastest " +
            number_text(fastest) + " m/s)";
  return true;
}

// Moving soil within h of water, found through a grid of cells h wide holding the water.
bool CascadeEventDetector::impact(const FieldFrame& frame, std::string& message) const {
  const auto* velocity = frame.find("velocity");
  if (!velocity) return false;
  const double speed_limit = events_.water_impact().speed();
  using Cell = std::tuple<long long, long long, long long>;
  const auto cell_of = [&](std::size_t i) {
    return Cell{std::llround(std::floor(frame.position[3 * i] / h_)), std::llround(std::floor(frame.position[3 * i + 1] / h_)),
                std::llround(std::floor(frame.position[3 * i + 2] / h_))};
  };
  std::map<Cell, std::vector<std::size_t>> water;
  for (std::size_t i = 0; i < frame.size(); ++i)
    if (frame.phase[i] == kWater) water[cell_of(i)].push_back(i);
  if (water.empty()) return false;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.phase[i] != kSoil) continue;
    const double speed = speed_of(*velocity, i);
    if (!(speed > speed_limit)) continue;
    const auto [cx, cy, cz] = cell_of(i);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = water.find(Cell{cx + dx, cy + dy, cz + dz});
          if (it == water.end()) continue;
          for (std::size_t j : it->second) {
            double r2 = 0;
            for (int a = 0; a < 3; ++a) r2 += std::pow(frame.position[3 * i + a] - frame.position[3 * j + a], 2);
            if (r2 < h_ * h_) {
              message = "soil at " + number_text(speed) + " m/s reaches the water at " + at(frame, i);
              return true;
            }
          }
        }
  }
  return false;
}

bool CascadeEventDetector::overtopped(const FieldFrame& frame, const v1::Overtopping& line, std::string& message) const {
  const int axis = line.axis() == "y" ? 1 : 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.phase[i] != kWater) continue;
    const double s = frame.position[3 * i + axis], z = frame.position[3 * i + 2];
    const bool beyond = line.below() ? s < line.position() : s > line.position();
    if (beyond && z > line.above()) {
      message = line.name() + ": water at " + at(frame, i) + " past " + line.axis() + " = " +
                number_text(line.position()) + " m above z = " + number_text(line.above()) + " m";
      return true;
    }
  }
  return false;
}

}  // namespace cascade
