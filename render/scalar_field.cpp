#include "render/scalar_field.h"

#include <cmath>

#include "render/egl_context.h"

namespace cascade::render {

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
      const int c = field_component_index(f->components, name.substr(underscore + 1));
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
