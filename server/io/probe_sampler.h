// Probes evaluated on a frame (docs/output.md, "probes.csv"):
//  point      a field interpolated at a position from one phase (Shepard interpolation with the
//             Wendland kernel: Σ f_j W_j V_j / Σ W_j V_j, V_j = m/ρ_j)
//  elevation  the water surface above a vertical line: going up from the lowest water particle
//             within 2h of the line, the height where the kernel-weighted water fraction
//             Σ V_j W(x − x_j) first drops below 1/2 (the wave-gauge rule of DualSPHysics)
//  front      the largest (or smallest) coordinate of a phase along an axis, minus `origin`
//  max, mean  of a field over a phase
// Fields are named as scalar_field() describes.
// A probe with nothing to measure (no particle of its phase near it) gives NaN. Particles that
// have left the domain are ignored.
#pragma once

#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/core/field_frame.h"
#include "server/core/kernel.h"

namespace cascade {

class ProbeSampler {
 public:
  ProbeSampler(const v1::ScenarioSpec& spec, double h, double particle_mass);

  std::vector<std::string> names() const;
  std::vector<double> sample(const FieldFrame& frame) const;

  // One scalar per particle for a probe field name: a one-component field of the frame by its
  // name (pressure, density, pore_pressure, saturation, porosity, plastic_strain, ...),
  // free_surface (0 or 1), speed (|velocity|), or a component of a vector field (velocity_x,
  // seepage_z, displacement_y: suffixes x, y, z, frame axes, so _z is vertical in 2D too) or of a
  // symmetric tensor field (stress_zz, effective_stress_xy: suffixes xx, yy, zz, xy, yz, zx).
  // Throws std::invalid_argument when the frame has no such field.
  static std::vector<double> scalar_field(const FieldFrame& frame, const std::string& name);

 private:
  double point(const v1::Probe& probe, const FieldFrame& frame) const;
  double elevation(const v1::Probe& probe, const FieldFrame& frame) const;
  double front(const v1::Probe& probe, const FieldFrame& frame) const;
  double reduce(const v1::Probe& probe, const FieldFrame& frame) const;
  double kernel(double r) const;
  bool in_domain(const FieldFrame& frame, std::size_t j) const;

  std::vector<v1::Probe> probes_;
  int dimensions_;
  double h_;
  double mass_;
  WendlandC2<double, 2> kernel2_;
  WendlandC2<double, 3> kernel3_;
  double lo_[3], hi_[3];  // domain box in frame coordinates; periodic axes unbounded
  double top_;  // domain top (z): where an elevation scan stops
};

}  // namespace cascade
