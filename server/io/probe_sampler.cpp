#include "server/io/probe_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cascade {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::uint8_t phase_code(const std::string& phase) {
  if (phase == "soil") return 1;
  if (phase == "boundary") return 2;
  return 0;  // water, the default
}

// Probe positions are in case coordinates: (x, z) in 2D, (x, y, z) in 3D. Frames are (x, y, z).
void to_frame_coordinates(const v1::Probe& probe, int dimensions, double out[3]) {
  out[0] = out[1] = out[2] = 0.0;
  if (dimensions == 2) {
    out[0] = probe.position_size() > 0 ? probe.position(0) : 0.0;
    out[2] = probe.position_size() > 1 ? probe.position(1) : 0.0;
  } else {
    for (int a = 0; a < 3 && a < probe.position_size(); ++a) out[a] = probe.position(a);
  }
}

}  // namespace

ProbeSampler::ProbeSampler(const v1::ScenarioSpec& spec, double h, double particle_mass)
    : probes_(spec.probes().begin(), spec.probes().end()),
      dimensions_(spec.dimensions()),
      h_(h),
      mass_(particle_mass),
      kernel2_(h),
      kernel3_(h),
      top_(spec.domain().max(spec.dimensions() - 1)) {
  // Case axes (x, z) or (x, y, z) → frame axes (x, y, z).
  const int frame_axis[3] = {0, dimensions_ == 2 ? 2 : 1, 2};
  for (int a = 0; a < 3; ++a) lo_[a] = -std::numeric_limits<double>::infinity(), hi_[a] = -lo_[a];
  for (int a = 0; a < dimensions_; ++a) {
    const bool periodic = a < spec.domain().periodic_size() && spec.domain().periodic(a);
    if (periodic) continue;
    lo_[frame_axis[a]] = spec.domain().min(a);
    hi_[frame_axis[a]] = spec.domain().max(a);
  }
}

bool ProbeSampler::counted(const FieldFrame& frame, const Rows* owned, std::size_t j) const {
  if (owned && !(*owned)[j]) return false;
  for (int a = 0; a < 3; ++a) {
    const double x = frame.position[3 * j + a];
    if (!(x >= lo_[a] && x <= hi_[a])) return false;
  }
  return true;
}

std::vector<std::string> ProbeSampler::names() const {
  std::vector<std::string> out;
  for (const auto& p : probes_) out.push_back(p.name());
  return out;
}

std::vector<ProbeSampler::Part> ProbeSampler::parts(const FieldFrame& frame, const Rows* owned) const {
  if (owned && owned->size() != frame.size()) throw std::invalid_argument("owned rows do not match the frame");
  std::vector<Part> out;
  out.reserve(probes_.size());
  for (const auto& p : probes_) {
    switch (p.kind()) {
      case v1::POINT: out.push_back(point(p, frame, owned)); break;
      case v1::ELEVATION: out.push_back(elevation(p, frame, owned)); break;
      case v1::FRONT: out.push_back(front(p, frame, owned)); break;
      case v1::MAX:
      case v1::MEAN: out.push_back(reduce(p, frame, owned)); break;
      default: out.push_back({});
    }
  }
  return out;
}

std::vector<double> ProbeSampler::combine(const std::vector<std::vector<Part>>& parts_of_processes) const {
  for (const auto& parts : parts_of_processes)
    if (parts.size() != probes_.size())
      throw std::invalid_argument("parts of " + std::to_string(parts.size()) + " probes, expected " +
                                  std::to_string(probes_.size()));
  std::vector<double> out;
  out.reserve(probes_.size());
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    const v1::Probe& probe = probes_[k];
    double sum = 0, weight = 0;
    double best = probe.kind() == v1::FRONT && probe.minimum() ? std::numeric_limits<double>::max()
                                                               : std::numeric_limits<double>::lowest();
    std::vector<double> column;
    for (const auto& parts : parts_of_processes) {
      const Part& part = parts[k];
      sum += part.sum;
      weight += part.weight;
      if (part.weight > 0)
        best = probe.kind() == v1::FRONT && probe.minimum() ? std::min(best, part.best) : std::max(best, part.best);
      column.insert(column.end(), part.column.begin(), part.column.end());
    }
    switch (probe.kind()) {
      case v1::POINT: out.push_back(weight > 0 ? sum / weight : kNaN); break;
      case v1::ELEVATION: out.push_back(elevation_of(std::move(column))); break;
      case v1::FRONT: out.push_back(weight > 0 ? best - probe.origin() : kNaN); break;
      case v1::MAX: out.push_back(weight > 0 ? best : kNaN); break;
      case v1::MEAN: out.push_back(weight > 0 ? sum / weight : kNaN); break;
      default: out.push_back(kNaN);
    }
  }
  return out;
}

// Per part: sum, weight, best, the column's length, the column.
std::vector<double> ProbeSampler::flatten(const std::vector<Part>& parts) {
  std::vector<double> numbers{double(parts.size())};
  for (const Part& part : parts) {
    numbers.insert(numbers.end(), {part.sum, part.weight, part.best, double(part.column.size())});
    numbers.insert(numbers.end(), part.column.begin(), part.column.end());
  }
  return numbers;
}

std::vector<ProbeSampler::Part> ProbeSampler::unflatten(const std::vector<double>& numbers) {
  std::size_t at = 0;
  const auto take = [&](std::size_t count) {
    if (numbers.size() - at < count) throw std::invalid_argument("probe parts cut short");
    at += count;
    return numbers.data() + at - count;
  };
  const double parts = *take(1);
  // Each part takes at least four numbers.
  if (!(parts >= 0 && parts == std::floor(parts) && parts <= double(numbers.size()) / 4))
    throw std::invalid_argument("probe parts: bad count");
  std::vector<Part> out(static_cast<std::size_t>(parts));
  for (Part& part : out) {
    const double* head = take(4);
    part.sum = head[0], part.weight = head[1], part.best = head[2];
    if (!(head[3] >= 0 && head[3] == std::floor(head[3]) && std::fmod(head[3], 4.0) == 0))
      throw std::invalid_argument("probe parts: bad column length");
    const double* column = take(static_cast<std::size_t>(head[3]));
    part.column.assign(column, column + static_cast<std::size_t>(head[3]));
  }
  if (at != numbers.size()) throw std::invalid_argument("probe parts: numbers left over");
  return out;
}

double ProbeSampler::kernel(double r) const { return dimensions_ == 2 ? kernel2_.value(r) : kernel3_.value(r); }

std::vector<double> ProbeSampler::scalar_field(const FieldFrame& frame, const std::string& name) {
  const std::size_t n = frame.size();
  if (name == "free_surface") {
    if (frame.free_surface.size() != n) throw std::invalid_argument("frame has no free_surface");
    return std::vector<double>(frame.free_surface.begin(), frame.free_surface.end());
  }
  if (name == "speed") {
    const auto* v = frame.find("velocity");
    if (!v || v->components != 3) throw std::invalid_argument("frame has no velocity");
    std::vector<double> out(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double* u = &v->values[3 * i];
      out[i] = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    }
    return out;
  }
  if (const auto* f = frame.find(name); f && f->components == 1) return f->values;
  // FIELD_COMPONENT: velocity_z, seepage_x, stress_zz, effective_stress_xy, ...
  const std::size_t split = name.rfind('_');
  if (split != std::string::npos) {
    const auto* f = frame.find(name.substr(0, split));
    const int c = f ? field_component_index(f->components, name.substr(split + 1)) : -1;
    if (c >= 0) {
      std::vector<double> out(n);
      for (std::size_t i = 0; i < n; ++i) out[i] = f->values[f->components * i + c];
      return out;
    }
  }
  throw std::invalid_argument("no scalar field '" + name + "' in the frame");
}

ProbeSampler::Part ProbeSampler::point(const v1::Probe& probe, const FieldFrame& frame, const Rows* owned) const {
  double x[3];
  to_frame_coordinates(probe, dimensions_, x);
  const auto values = scalar_field(frame, probe.field());
  const auto* density = frame.find("numerical_density");
  const std::uint8_t phase = phase_code(probe.phase());
  Part part;
  for (std::size_t j = 0; j < frame.size(); ++j) {
    if (frame.phase[j] != phase || !counted(frame, owned, j)) continue;
    const double* p = &frame.position[3 * j];
    const double r = std::sqrt((p[0] - x[0]) * (p[0] - x[0]) + (p[1] - x[1]) * (p[1] - x[1]) + (p[2] - x[2]) * (p[2] - x[2]));
    const double w = kernel(r);
    if (w <= 0) continue;
    const double volume = mass_ / (density ? density->values[j] : 1000.0);
    part.sum += values[j] * w * volume;
    part.weight += w * volume;
  }
  return part;
}

ProbeSampler::Part ProbeSampler::elevation(const v1::Probe& probe, const FieldFrame& frame, const Rows* owned) const {
  double x[3];
  to_frame_coordinates(probe, dimensions_, x);
  if (dimensions_ == 2) x[1] = 0.0;
  else if (probe.position_size() == 2) x[1] = probe.position(1);
  const auto* density = frame.find("numerical_density");
  // The water within 2h of the vertical line, the only particles the scan can see.
  Part part;
  for (std::size_t j = 0; j < frame.size(); ++j) {
    if (frame.phase[j] != 0 || !counted(frame, owned, j)) continue;
    const double* p = &frame.position[3 * j];
    const double d2 = (p[0] - x[0]) * (p[0] - x[0]) + (dimensions_ == 3 ? (p[1] - x[1]) * (p[1] - x[1]) : 0.0);
    if (d2 >= 4 * h_ * h_) continue;
    part.column.insert(part.column.end(), {double(frame.id[j]), d2, p[2], mass_ / (density ? density->values[j] : 1000.0)});
  }
  return part;
}

// The scan up a column of (id, horizontal distance², z, volume) entries, taken in id order.
double ProbeSampler::elevation_of(std::vector<double> column) const {
  struct Near {
    double id, horizontal2, z, volume;
  };
  std::vector<Near> near(column.size() / 4);
  for (std::size_t n = 0; n < near.size(); ++n)
    near[n] = {column[4 * n], column[4 * n + 1], column[4 * n + 2], column[4 * n + 3]};
  if (near.empty()) return kNaN;
  std::sort(near.begin(), near.end(), [](const Near& a, const Near& b) { return a.id < b.id; });
  double lowest = std::numeric_limits<double>::max();
  for (const Near& n : near) lowest = std::min(lowest, n.z);
  auto fraction = [&](double z) {
    double c = 0;
    for (const auto& n : near) c += n.volume * kernel(std::sqrt(n.horizontal2 + (n.z - z) * (n.z - z)));
    return c;
  };
  const double step = 0.1 * h_;
  double z_prev = lowest, c_prev = fraction(lowest);
  for (double z = lowest + step; z <= top_ + 2 * h_; z += step) {
    const double c = fraction(z);
    if (c_prev >= 0.5 && c < 0.5) return z_prev + (c_prev - 0.5) / (c_prev - c) * (z - z_prev);
    z_prev = z, c_prev = c;
  }
  return kNaN;
}

ProbeSampler::Part ProbeSampler::front(const v1::Probe& probe, const FieldFrame& frame, const Rows* owned) const {
  const int axis = probe.axis() == "x" ? 0 : probe.axis() == "y" ? (dimensions_ == 2 ? 2 : 1) : 2;
  const std::uint8_t phase = phase_code(probe.phase());
  Part part;
  part.best = probe.minimum() ? std::numeric_limits<double>::max() : std::numeric_limits<double>::lowest();
  for (std::size_t j = 0; j < frame.size(); ++j) {
    if (frame.phase[j] != phase || !counted(frame, owned, j)) continue;
    const double c = frame.position[3 * j + axis];
    part.best = probe.minimum() ? std::min(part.best, c) : std::max(part.best, c);
    part.weight += 1;
  }
  return part;
}

ProbeSampler::Part ProbeSampler::reduce(const v1::Probe& probe, const FieldFrame& frame, const Rows* owned) const {
  const auto values = scalar_field(frame, probe.field());
  const std::uint8_t phase = phase_code(probe.phase());
  Part part;
  part.best = std::numeric_limits<double>::lowest();
  for (std::size_t j = 0; j < frame.size(); ++j) {
    if (frame.phase[j] != phase || !counted(frame, owned, j)) continue;
    part.best = std::max(part.best, values[j]);
    part.sum += values[j];
    part.weight += 1;
  }
  return part;
}

}  // namespace cascade
