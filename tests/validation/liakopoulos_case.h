// cases/liakopoulos.yaml as the validation tests run it (test_liakopoulos.cpp explains why): at
// dp = 0.05 m, with K_sat α times larger and the initialisation α times shorter.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "tests/reference/liakopoulos_reference.h"

namespace cascade::testing {

inline std::vector<std::string> accelerated_liakopoulos(double alpha) {
  char conductivity[64], duration[64];
  std::snprintf(conductivity, sizeof conductivity, "materials[0].soil.saturated_conductivity=%.10g",
                alpha * reference::LiakopoulosMaterial::saturated_conductivity);
  std::snprintf(duration, sizeof duration, "initialisation.duration=%.10g", 20.0 / alpha);
  return {"dp=0.05", conductivity, duration};
}

}  // namespace cascade::testing
