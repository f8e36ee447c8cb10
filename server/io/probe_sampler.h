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
// A run split over processes samples its probes without gathering its particles: each process
// takes the parts of its own particles (parts), a few numbers per probe, and process 0 combines
// them (combine) into the values that all particles give. One process takes the same path.
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
  std::vector<double> sample(const FieldFrame& frame) const { return combine({parts(frame)}); }

  // What some particles give one probe.
  struct Part {
    double sum = 0, weight = 0;  // point: Σ f W V and Σ W V; mean: Σ f and the count; front, max: the count
    double best = 0;             // front, max: the largest (front: or smallest) coordinate or value
    std::vector<double> column;  // elevation: id, horizontal distance², z and volume of each water
                                 // particle within 2h of the line
  };
  // The parts of the rows of `frame` that `owned` marks (one entry per row; null: every row), one
  // per probe.
  std::vector<Part> parts(const FieldFrame& frame, const std::vector<char>* owned = nullptr) const;
  // The probes' values from the parts of every process: the sums added, the extremes taken, an
  // elevation's columns joined in id order (the order of one process's frame).
  std::vector<double> combine(const std::vector<std::vector<Part>>& parts_of_processes) const;
  // The parts as numbers for a message, and back; unflatten throws std::invalid_argument on a
  // message that is not `flatten`'s.
  static std::vector<double> flatten(const std::vector<Part>& parts);
  static std::vector<Part> unflatten(const std::vector<double>& numbers);

  // One scalar per particle for a probe field name: a one-component field of the frame by its
  // name (pressure, density, pore_pressure, saturation, porosity, plastic_strain, ...),
  // free_surface (0 or 1), speed (|velocity|), or a component of a vector field (velocity_x,
  // seepage_z, displacement_y: suffixes x, y, z, frame axes, so _z is vertical in 2D too) or of a
  // symmetric tensor field (stress_zz, effective_stress_xy: suffixes xx, yy, zz, xy, yz, zx).
  // Throws std::invalid_argument when the frame has no such field.
  static std::vector<double> scalar_field(const FieldFrame& frame, const std::string& name);

 private:
  using Rows = std::vector<char>;
  Part point(const v1::Probe& probe, const FieldFrame& frame, const Rows* owned) const;
  Part elevation(const v1::Probe& probe, const FieldFrame& frame, const Rows* owned) const;
  Part front(const v1::Probe& probe, const FieldFrame& frame, const Rows* owned) const;
  Part reduce(const v1::Probe& probe, const FieldFrame& frame, const Rows* owned) const;
  double elevation_of(std::vector<double> column) const;
  double kernel(double r) const;
  // Whether row j is counted: owned by this process and within the domain.
  bool counted(const FieldFrame& frame, const Rows* owned, std::size_t j) const;

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
