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

bool ProbeSampler::in_domain(const FieldFrame& frame, std::size_t j) const {
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

std::vector<double> ProbeSampler::sample(const FieldFrame& frame) const {
  std::vector<double> out;
  out.reserve(probes_.size());
  for (const auto& p : probes_) {
    switch (p.kind()) {
      case v1::POINT: out.push_back(point(p, frame)); break;
      case v1::ELEVATION: out.push_back(elevation(p, frame)); break;
      case v1::FRONT: out.push_back(front(p, frame)); break;
      case v1::MAX:
      case v1::MEAN: out.push_back(reduce(p, frame)); break;
      default: out.push_back(kNaN);
    }
  }
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

double ProbeSampler::point(const v1::Probe& probe, const FieldFrame& frame) const {
  double x[3];
  to_frame_coordinates(probe, dimensions_, x);
  const auto values = scalar_field(frame, probe.field());
  const auto* density = frame.find("numerical_density");
  const std::uint8_t phase = phase_code(probe.phase());
  double sum = 0, weight = 0;
  for (std::size_t j = 0; j < frame.size(); ++j) {
    if (frame.phase[j] != phase || !in_domain(frame, j)) continue;
    const double* p = &frame.position[3 * j];
    const double r = std::sqrt((p[0] - x[0]) * (p[0] - x[0]) + (p[1] - x[1]) * (p[1] - x[1]) + (p[2] - x[2]) * (p[2] - x[2]));
    const double w = kernel(r);
    if (w <= 0) continue;
    const double volume = mass_ / (density ? density->values[j] : 1000.0);
    sum += values[j] * w * volume;
    weight += w * volume;
  }
  return weight > 0 ? sum / weight : kNaN;
}

double ProbeSampler::elevation(const v1::Probe& probe, const FieldFrame& frame) const {
  double x[3];
  to_frame_coordinates(probe, dimensions_, x);
  if (dimensions_ == 2) x[1] = 0.0;
  else if (probe.position_size() == 2) x[1] = probe.position(1);
  const auto* density = frame.find("numerical_density");
  // The water within 2h of the vertical line, the only particles the scan can see.
  struct Near {
    double horizontal2, z, volume;
  };
  std::vector<Near> column;
  double lowest = std::numeric_limits<double>::max();
  for (std::size_t j = 0; j < frame.size(); ++j) {
    if (frame.phase[j] != 0 || !in_domain(frame, j)) continue;
    const double* p = &frame.position[3 * j];
    const double d2 = (p[0] - x[0]) * (p[0] - x[0]) + (dimensions_ == 3 ? (p[1] - x[1]) * (p[1] - x[1]) : 0.0);
    if (d2 >= 4 * h_ * h_) continue;
    column.push_back({d2, p[2], mass_ / (density ? density->values[j] : 1000.0)});
    lowest = std::min(lowest, p[2]);
  }
  if (column.empty()) return kNaN;
  auto fraction = [&](double z) {
    double c = 0;
    for (const auto& n : column) c += n.volume * kernel(std::sqrt(n.horizontal2 + (n.z - z) * (n.z - z)));
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

double ProbeSampler::front(const v1::Probe& probe, const FieldFrame& frame) const {
  const int axis = probe.axis() == "x" ? 0 : probe.axis() == "y" ? (dimensions_ == 2 ? 2 : 1) : 2;
  const std::uint8_t phase = phase_code(probe.phase());
  double best = probe.minimum() ? std::numeric_limits<double>::max() : std::numeric_limits<double>::lowest();
  bool any = false;
  for (std::size_t j = 0; j < frame.size(); ++j) {
    if (frame.phase[j] != phase || !in_domain(frame, j)) continue;
    const double c = frame.position[3 * j + axis];
    best = probe.minimum() ? std::min(best, c) : std::max(best, c);
    any = true;
  }
  return any ? best - probe.origin() : kNaN;
}

double ProbeSampler::reduce(const v1::Probe& probe, const FieldFrame& frame) const {
  const auto values = scalar_field(frame, probe.field());
  const std::uint8_t phase = phase_code(probe.phase());
  double best = std::numeric_limits<double>::lowest(), sum = 0;
  std::size_t count = 0;
  for (std::size_t j = 0; j < frame.size(); ++j) {
    if (frame.phase[j] != phase || !in_domain(frame, j)) continue;
    best = std::max(best, values[j]);
    sum += values[j];
    ++count;
  }
  if (count == 0) return kNaN;
  return probe.kind() == v1::MAX ? best : sum / double(count);
}

}  // namespace cascade
