// How deep water and soil particles lie inside a case's solids, from the case's own geometry (the
// boundary bodies' shapes, not the dummy particles the engine builds from them): the depth of a
// point inside the union of the boundary regions is its distance to their wetted surface, the
// parts of each region's surface not covered by another boundary region (periodic images are not
// taken into account). A particle centre deeper than dp/2 has its whole lattice cell inside the
// solid (issue 13, item 1).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/core/field_frame.h"
#include "server/core/types.h"
#include "server/scenario/geometry.h"
#include "tests/validation/validation_table.h"

namespace cascade::testing {

class SolidDepth {
 public:
  explicit SolidDepth(const v1::ScenarioSpec& spec) {
    const int dims = spec.dimensions();
    const int axis[3] = {0, dims == 2 ? 2 : 1, 2};
    Aabb domain{Vec3::Zero(), Vec3::Zero()};
    for (int c = 0; c < dims; ++c) domain.lo[axis[c]] = spec.domain().min(c), domain.hi[axis[c]] = spec.domain().max(c);
    const Aabb face_bounds = domain.expanded((domain.hi - domain.lo).norm() + 10.0 * spec.dp());
    const double gap = 1e-3 * spec.dp();
    for (int i = 0; i < spec.bodies_size(); ++i) {
      const v1::Body& b = spec.bodies(i);
      if (b.kind() != v1::BOUNDARY) continue;
      const std::string key = "bodies[" + std::to_string(i) + "]";
      std::vector<Shape> subtract;
      for (int k = 0; k < b.subtract_size(); ++k)
        subtract.push_back(
            shape_from_spec(b.subtract(k), dims, face_bounds, spec.terrain().grid(), spec.dp(), key + ".subtract"));
      solids_.emplace_back(shape_from_spec(b.shape(), dims, face_bounds, spec.terrain().grid(), spec.dp(), key + ".shape"),
                           std::move(subtract));
    }
    for (std::size_t r = 0; r < solids_.size(); ++r) {
      std::vector<Face> faces = solids_[r].surface(gap);
      for (std::size_t q = 0; q < solids_.size(); ++q)
        if (q != r) faces = cut_by_region(faces, solids_[q], gap);
      wetted_.insert(wetted_.end(), faces.begin(), faces.end());
    }
  }

  // Depth of x inside the solids (m); 0 outside them.
  double depth(const Vec3& x) const {
    if (std::none_of(solids_.begin(), solids_.end(), [&](const Region& r) { return r.contains(x); })) return 0.0;
    double nearest = INFINITY;
    for (const Face& f : wetted_) nearest = std::min(nearest, (f.closest_point(x) - x).norm());
    return nearest;
  }

  // The water and soil particles of a frame (flagged lost or not) whose centres lie deeper than
  // `limit` inside the solids, and the deepest depth among all of them.
  struct Count {
    std::size_t deeper = 0;
    double deepest = 0;
    void keep_worst(const Count& c) {  // over samples: the most particles at once, the deepest
      deeper = std::max(deeper, c.deeper);
      deepest = std::max(deepest, c.deepest);
    }
  };
  Count inside(const FieldFrame& f, double limit) const {
    Count c;
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (f.phase[i] == std::uint8_t(Phase::boundary)) continue;
      const double d = depth(Vec3(f.position[3 * i], f.position[3 * i + 1], f.position[3 * i + 2]));
      c.deepest = std::max(c.deepest, d);
      if (d > limit) ++c.deeper;
    }
    return c;
  }

 private:
  std::vector<Region> solids_;
  std::vector<Face> wetted_;
};

// The two figures of "nothing inside a wall" (issue 13, item 1): the most particles deeper than
// dp/2 at any one sample, which must be 0, and the deepest depth reached, at most dp/2.
inline void validate_outside_solids(const std::string& case_name, const SolidDepth::Count& worst, double half_spacing,
                                    const std::string& when) {
  const std::string reference = "impenetrable walls: no centre deeper than dp/2 inside a solid";
  CASCADE_VALIDATE({.case_name = case_name, .reference = reference,
                    .metric = "water and soil particles deeper than dp/2 inside the walls, most " + when,
                    .measured = double(worst.deeper), .reference_value = 0, .bound = Bound::at_most,
                    .tolerance_source = "exact: a count"});
  CASCADE_VALIDATE({.case_name = case_name, .reference = reference,
                    .metric = "deepest water or soil particle inside the walls " + when + " [mm]",
                    .measured = 1e3 * worst.deepest, .reference_value = 1e3 * half_spacing, .bound = Bound::at_most,
                    .tolerance_source = "dp/2: a centre deeper has its whole lattice cell inside the solid"});
}

// A run's wall figures over its samples: every frame passed to `sample` is counted, `validate`
// prints and records the worst of them (validate_outside_solids).
class WallWatch {
 public:
  explicit WallWatch(const v1::ScenarioSpec& spec) : solids_(spec), half_spacing_(0.5 * spec.dp()) {}
  void sample(const FieldFrame& f) { worst_.keep_worst(solids_.inside(f, half_spacing_)); }
  const SolidDepth::Count& worst() const { return worst_; }
  void validate(const std::string& case_name, const std::string& when) const {
    std::printf("%s: deepest %.3g mm inside a wall, at most %zu particles deeper than dp/2 %s\n", case_name.c_str(),
                1e3 * worst_.deepest, worst_.deeper, when.c_str());
    validate_outside_solids(case_name, worst_, half_spacing_, when);
  }

 private:
  SolidDepth solids_;
  double half_spacing_;
  SolidDepth::Count worst_;
};

}  // namespace cascade::testing
