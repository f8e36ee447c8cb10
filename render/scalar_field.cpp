#include "render/scalar_field.h"

#include <cmath>

#include "render/egl_context.h"

namespace cascade::render {

namespace {

// The component a suffix selects in a field of `components` values, or -1.
int component_index(const std::string& suffix, int components) {
  static const char* const kVector[] = {"x", "y", "z"};
  static const char* const kVoigt[] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  if (components == 3)
    for (int c = 0; c < 3; ++c)
      if (suffix == kVector[c]) return c;
  if (components == 6)
    for (int c = 0; c < 6; ++c)
      if (suffix == kVoigt[c]) return c;
  return -1;
}

}  // namespace

ScalarField scalar_field(const FieldFrame& frame, const std::string& name) {
  const std::size_t n = frame.size();
  if (const FieldFrame::RealField* f = frame.find(name)) {
    if (f->components == 1) return {name, f->units, f->values};
    if (f->components == 3) {
      ScalarField magnitude{name, f->units, std::vector<double>(n)};
      for (std::size_t i = 0; i < n; ++i)
        magnitude.values[i] = std::hypot(f->values[3 * i], f->values[3 * i + 1], f->values[3 * i + 2]);
      return magnitude;
    }
  }
  const auto underscore = name.rfind('_');
  if (underscore != std::string::npos) {
    if (const FieldFrame::RealField* f = frame.find(name.substr(0, underscore))) {
      const int c = component_index(name.substr(underscore + 1), f->components);
      if (c >= 0) {
        ScalarField component{name, f->units, std::vector<double>(n)};
        for (std::size_t i = 0; i < n; ++i) component.values[i] = f->values[i * std::size_t(f->components) + std::size_t(c)];
        return component;
      }
    }
  }
  std::string known;
  for (const auto& f : frame.fields) known += (known.empty() ? "" : ", ") + f.name;
  throw RenderError("field '" + name + "' is not in the frame (it has " + known +
                    "; vectors take _x/_y/_z, tensors _xx/_yy/_zz/_xy/_yz/_zx)");
}

}  // namespace cascade::render
