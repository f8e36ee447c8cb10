// One output frame on the host: every field of every particle at one simulated time, in the
// layout of docs/output.md. Particles are ordered by id. Writers and probes read only this.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cascade {

struct FieldFrame {
  struct RealField {
    std::string name;      // e.g. "velocity", "pressure"
    std::string units;     // e.g. "m/s", "Pa"
    int components = 1;    // 1 for scalars, 3 for vectors, 6 for symmetric tensors (Voigt)
    std::vector<double> values;  // N × components, row-major
  };

  double time = 0.0;             // simulated time (s)
  std::uint64_t step = 0;
  int dimensions = 3;            // of the case; positions are always written with 3 components
  std::vector<double> position;  // N × 3, z up; 2D cases have y = 0
  std::vector<std::uint8_t> phase;  // N: 0 water, 1 soil, 2 boundary
  std::vector<std::uint32_t> id;    // N
  std::vector<std::uint8_t> free_surface;  // N: 1 for a soil particle on the free surface (Eq. 38);
                                           // empty when the case has no soil
  std::vector<RealField> fields;    // velocity (N×3), pressure, density, ...

  std::size_t size() const { return id.size(); }
  const RealField* find(const std::string& name) const {
    for (const auto& f : fields)
      if (f.name == name) return &f;
    return nullptr;
  }
};

// Which rows of a process's local frame (Engine::local_frame) it owns: those whose field "process"
// is `process`, or every row of a frame without that field (one process owns the whole run).
inline std::vector<char> owned_rows(const FieldFrame& frame, int process) {
  const FieldFrame::RealField* owner = frame.find("process");
  std::vector<char> owned(frame.size(), 1);
  if (owner)
    for (std::size_t i = 0; i < frame.size(); ++i) owned[i] = owner->values[i] == double(process);
  return owned;
}

// The first id of process r's block when the `particles` ids of a run are dealt out in id order to
// `processes` processes as evenly as can be (Engine::frame_block); r = processes gives particles.
// (Ids are 32-bit: the product fits 64 bits.)
inline std::size_t id_block_start(std::size_t particles, int processes, int r) {
  return std::size_t(std::uint64_t(particles) * std::uint64_t(r) / std::uint64_t(processes));
}

// The component a name suffix selects in a field of `components` values: x, y, z of a vector,
// xx, yy, zz, xy, yz, zx of a symmetric tensor (Voigt order, as the fields hold it); −1 for none.
inline int field_component_index(int components, const std::string& suffix) {
  static const char* const kVector[3] = {"x", "y", "z"};
  static const char* const kTensor[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  if (components == 3)
    for (int c = 0; c < 3; ++c)
      if (suffix == kVector[c]) return c;
  if (components == 6)
    for (int c = 0; c < 6; ++c)
      if (suffix == kTensor[c]) return c;
  return -1;
}

}  // namespace cascade
