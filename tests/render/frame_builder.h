// Small hand-made frames for the renderer's tests.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "server/core/field_frame.h"

namespace cascade::render::test {

struct TestParticle {
  std::array<double, 3> position;
  std::uint8_t phase;  // 0 water, 1 soil, 2 boundary
  double value;        // of the frame's one field, "pressure" [Pa]
};

inline FieldFrame make_frame(int dimensions, const std::vector<TestParticle>& particles) {
  FieldFrame f;
  f.time = 1.5;
  f.step = 42;
  f.dimensions = dimensions;
  FieldFrame::RealField pressure{"pressure", "Pa", 1, {}};
  FieldFrame::RealField velocity{"velocity", "m/s", 3, {}};
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const TestParticle& p = particles[i];
    f.position.insert(f.position.end(), p.position.begin(), p.position.end());
    f.phase.push_back(p.phase);
    f.id.push_back(std::uint32_t(i));
    pressure.values.push_back(p.value);
    // A vector whose magnitude is the value: (0.6 v, 0, 0.8 v).
    velocity.values.insert(velocity.values.end(), {0.6 * p.value, 0.0, 0.8 * p.value});
  }
  f.fields = {pressure, velocity};
  return f;
}

}  // namespace cascade::render::test
