// A number as error messages show it: up to 10 significant digits, as the user wrote it where it
// was exact.
#pragma once

#include <sstream>
#include <string>

namespace cascade {

inline std::string number_text(double v) {
  std::ostringstream out;
  out.precision(10);
  out << v;
  return out.str();
}

}  // namespace cascade
