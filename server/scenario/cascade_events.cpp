#include "server/scenario/cascade_events.h"

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include "server/scenario/number_text.h"

namespace cascade {
namespace {

constexpr std::uint8_t kWater = 0, kSoil = 1;

double speed_of(const FieldFrame::RealField& velocity, std::size_t i) {
  const double* v = &velocity.values[3 * i];
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

std::string at(const CascadeEventDetector::Found& f) {
  return "(" + number_text(f.position[0]) + ", " + number_text(f.position[1]) + ", " + number_text(f.position[2]) + ") m";
}

// Row i as a Found, if it comes before `lowest` in id order.
void keep_lowest(const FieldFrame& frame, std::size_t i, double speed, CascadeEventDetector::Found& lowest) {
  if (!(double(frame.id[i]) < lowest.id)) return;
  lowest.id = frame.id[i];
  for (int a = 0; a < 3; ++a) lowest.position[a] = frame.position[3 * i + a];
  lowest.speed = speed;
}

void keep_lowest(const CascadeEventDetector::Found& f, CascadeEventDetector::Found& lowest) {
  if (f.id < lowest.id) lowest = f;
}

bool counted(const std::vector<char>* owned, std::size_t i) { return !owned || (*owned)[i]; }

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

CascadeEventDetector::Part CascadeEventDetector::part(const FieldFrame& frame, double ponding_pressure,
                                                      const Rows* owned) const {
  if (owned && owned->size() != frame.size()) throw std::invalid_argument("owned rows do not match the frame");
  Part part;
  if (!enabled_) return part;
  if (events_.ponding_started()) ponding(frame, owned, ponding_pressure, part);
  if (events_.has_landslide_onset()) landslide(frame, owned, part);
  if (events_.has_water_impact()) impact(frame, owned, part);
  for (const Line& l : lines_) part.overtopping.push_back(overtopped(frame, owned, l.spec));
  return part;
}

std::vector<CascadeEvent> CascadeEventDetector::observe(const std::vector<Part>& parts,
                                                        const std::vector<double>& probe_values,
                                                        double ponding_pressure) {
  std::vector<CascadeEvent> fired;
  if (!enabled_) return fired;
  Part all;
  all.overtopping.resize(lines_.size());
  for (const Part& p : parts) {
    if (p.overtopping.size() != lines_.size())
      throw std::invalid_argument("a part of " + std::to_string(p.overtopping.size()) + " overtopping lines, expected " +
                                  std::to_string(lines_.size()));
    all.ponding_count += p.ponding_count;
    keep_lowest(p.ponding, all.ponding);
    all.slide_volume += p.slide_volume;
    all.slide_fastest = std::fmax(all.slide_fastest, p.slide_fastest);
    keep_lowest(p.impact, all.impact);
    for (std::size_t l = 0; l < lines_.size(); ++l) keep_lowest(p.overtopping[l], all.overtopping[l]);
  }
  if (events_.ponding_started() && !ponding_fired_ && all.ponding_count > 0) {
    ponding_fired_ = true;
    fired.push_back({"ponding_started", std::to_string(std::uint64_t(all.ponding_count)) + " free-surface soil particle(s) at p_max = " +
                                            number_text(ponding_pressure) + " Pa, e.g. at " + at(all.ponding)});
  }
  if (events_.has_landslide_onset() && !landslide_fired_ && all.slide_volume > events_.landslide_onset().volume()) {
    const v1::LandslideOnset& l = events_.landslide_onset();
    landslide_fired_ = true;
    fired.push_back({"landslide_onset", number_text(all.slide_volume) + (dimensions_ == 2 ? " m²" : " m³") +
                                            " of soil with κ > " + number_text(l.plastic_strain()) + " faster than " +
                                            number_text(l.speed()) + " m/s (fastest " + number_text(all.slide_fastest) +
                                            " m/s)"});
  }
  if (events_.has_water_impact() && !impact_fired_ && std::isfinite(all.impact.id)) {
    impact_fired_ = true;
    fired.push_back({"water_impact",
                     "soil at " + number_text(all.impact.speed) + " m/s reaches the water at " + at(all.impact)});
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
  for (std::size_t k = 0; k < lines_.size(); ++k) {
    Line& l = lines_[k];
    if (l.fired || !std::isfinite(all.overtopping[k].id)) continue;
    l.fired = true;
    fired.push_back({"overtopping", l.spec.name() + ": water at " + at(all.overtopping[k]) + " past " + l.spec.axis() +
                                        " = " + number_text(l.spec.position()) + " m above z = " +
                                        number_text(l.spec.above()) + " m"});
  }
  return fired;
}

// Per Found: id (−1 for none), position, speed.
std::vector<double> CascadeEventDetector::flatten(const Part& part) {
  std::vector<double> numbers{part.ponding_count, part.slide_volume, part.slide_fastest,
                              double(part.overtopping.size())};
  const auto put = [&](const Found& f) {
    numbers.insert(numbers.end(), {std::isfinite(f.id) ? f.id : -1.0, f.position[0], f.position[1], f.position[2], f.speed});
  };
  put(part.ponding);
  put(part.impact);
  for (const Found& f : part.overtopping) put(f);
  return numbers;
}

CascadeEventDetector::Part CascadeEventDetector::unflatten(const std::vector<double>& numbers) {
  if (numbers.size() < 4) throw std::invalid_argument("event part cut short");
  const double lines = numbers[3];
  if (!(lines >= 0 && lines == std::floor(lines)) || numbers.size() != 4 + 5 * (2 + std::size_t(lines)))
    throw std::invalid_argument("event part of " + std::to_string(numbers.size()) + " numbers");
  Part part;
  part.ponding_count = numbers[0], part.slide_volume = numbers[1], part.slide_fastest = numbers[2];
  std::size_t at = 4;
  const auto take = [&](Found& f) {
    f.id = numbers[at] < 0 ? std::numeric_limits<double>::infinity() : numbers[at];
    for (int a = 0; a < 3; ++a) f.position[a] = numbers[at + 1 + a];
    f.speed = numbers[at + 4];
    at += 5;
  };
  take(part.ponding);
  take(part.impact);
  part.overtopping.resize(std::size_t(lines));
  for (Found& f : part.overtopping) take(f);
  return part;
}

// A free-surface soil particle at p_max: the Eq. 39 switch holds it there once it has reached it.
void CascadeEventDetector::ponding(const FieldFrame& frame, const Rows* owned, double ponding_pressure, Part& part) const {
  const auto* p = frame.find("pore_pressure");
  if (!p || frame.free_surface.size() != frame.size()) return;
  const double tolerance = 1e-6 * (1.0 + std::fabs(ponding_pressure));
  for (std::size_t i = 0; i < frame.size(); ++i)
    if (counted(owned, i) && frame.phase[i] == kSoil && frame.free_surface[i] &&
        p->values[i] >= ponding_pressure - tolerance) {
      part.ponding_count += 1;
      keep_lowest(frame, i, 0.0, part.ponding);
    }
}

void CascadeEventDetector::landslide(const FieldFrame& frame, const Rows* owned, Part& part) const {
  const v1::LandslideOnset& l = events_.landslide_onset();
  const auto* kappa = frame.find("plastic_strain");
  const auto* velocity = frame.find("velocity");
  if (!kappa || !velocity) return;
  const double particle_volume = std::pow(dp_, dimensions_);
  for (std::size_t i = 0; i < frame.size(); ++i)
    if (counted(owned, i) && frame.phase[i] == kSoil && kappa->values[i] > l.plastic_strain()) {
      const double speed = speed_of(*velocity, i);
      if (speed > l.speed()) {
        part.slide_volume += particle_volume;
        part.slide_fastest = std::fmax(part.slide_fastest, speed);
      }
    }
}

// Moving soil within h of water, found through a grid of cells h wide holding the water.
void CascadeEventDetector::impact(const FieldFrame& frame, const Rows* owned, Part& part) const {
  const auto* velocity = frame.find("velocity");
  if (!velocity) return;
  const double speed_limit = events_.water_impact().speed();
  using Cell = std::tuple<long long, long long, long long>;
  const auto cell_of = [&](std::size_t i) {
    return Cell{std::llround(std::floor(frame.position[3 * i] / h_)), std::llround(std::floor(frame.position[3 * i + 1] / h_)),
                std::llround(std::floor(frame.position[3 * i + 2] / h_))};
  };
  std::map<Cell, std::vector<std::size_t>> water;
  for (std::size_t i = 0; i < frame.size(); ++i)
    if (frame.phase[i] == kWater) water[cell_of(i)].push_back(i);
  if (water.empty()) return;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (!counted(owned, i) || frame.phase[i] != kSoil) continue;
    const double speed = speed_of(*velocity, i);
    if (!(speed > speed_limit)) continue;
    const auto [cx, cy, cz] = cell_of(i);
    bool touches = false;
    for (long long dx = -1; dx <= 1 && !touches; ++dx)
      for (long long dy = -1; dy <= 1 && !touches; ++dy)
        for (long long dz = -1; dz <= 1 && !touches; ++dz) {
          const auto it = water.find(Cell{cx + dx, cy + dy, cz + dz});
          if (it == water.end()) continue;
          for (std::size_t j : it->second) {
            double r2 = 0;
            for (int a = 0; a < 3; ++a) r2 += std::pow(frame.position[3 * i + a] - frame.position[3 * j + a], 2);
            if (r2 < h_ * h_) touches = true;
          }
        }
    if (touches) keep_lowest(frame, i, speed, part.impact);
  }
}

CascadeEventDetector::Found CascadeEventDetector::overtopped(const FieldFrame& frame, const Rows* owned,
                                                             const v1::Overtopping& line) const {
  const int axis = line.axis() == "y" ? 1 : 0;
  Found lowest;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (!counted(owned, i) || frame.phase[i] != kWater) continue;
    const double s = frame.position[3 * i + axis], z = frame.position[3 * i + 2];
    const bool beyond = line.below() ? s < line.position() : s > line.position();
    if (beyond && z > line.above()) keep_lowest(frame, i, 0.0, lowest);
  }
  return lowest;
}

}  // namespace cascade
