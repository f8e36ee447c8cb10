// The per-particle scalar a snapshot colours by: a scalar field of the frame, the magnitude of a
// vector field ("velocity"), or one component of a vector (velocity_z) or a symmetric tensor in
// Voigt order (stress_zz, effective_stress_xy).
#pragma once

#include <string>
#include <vector>

#include "server/core/field_frame.h"

namespace cascade::render {

struct ScalarField {
  std::string name, units;
  std::vector<double> values;  // one per particle
};

// Throws RenderError naming the field and the frame's fields when there is no such field.
ScalarField scalar_field(const FieldFrame& frame, const std::string& name);

}  // namespace cascade::render
