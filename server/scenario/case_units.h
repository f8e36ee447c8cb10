// Units in case files: a double field whose schema names its SI unit (the
// `unit` option of proto/cascade/v1/units.proto) may be written as "<number>
// <unit>" (`end_time: 36 h`, `rainfall_intensity: 45 mm/h`), and a hyetograph
// names the units of its columns. Each unit is an exact factor to its SI unit,
// applied as one multiplication or one division, so the SI value is the double
// nearest to the exact one (45 mm/h is 45 / 3.6e6 m/s).
#pragma once

#include <google/protobuf/descriptor.h>

#include <optional>
#include <string>

namespace cascade {

struct CaseUnit {
  const char *name;   // as written in a case file: "mm/h"
  const char *si;     // the SI unit of its dimension: "m/s"
  double multiplier;  // SI value = value × multiplier / divisor, one of them 1
  double divisor;

  double to_si(double value) const { return multiplier != 1 ? value * multiplier : value / divisor; }
};

// The unit written `name`, or nullptr.
const CaseUnit *find_case_unit(const std::string &name);

// The SI unit a field's schema names (its `unit` option), empty for a plain
// number.
std::string si_unit_of(const google::protobuf::FieldDescriptor *field);

// The dimension of SI unit `si` for messages ("a speed" for "m/s"), or empty
// when no unit of the table has that SI unit.
std::string dimension_name(const std::string &si);

// The units of SI unit `si`, as a list for messages: "m/s, mm/h, mm/day, cm/h,
// m/h, m/day".
std::string unit_names(const std::string &si);

// Why `name` is not a unit of SI unit `si` ("unknown unit 'mm/hr' (units of a
// speed: ...)", "takes a speed (m/s); 'mm' is a length"), or empty when it is
// one.
std::string unit_problem(const std::string &name, const std::string &si);

// "45 mm/h" split into its number and its unit name, or nothing when the text
// is not a number, one or more spaces and a unit name. The number is read as
// YAML reads numbers.
struct NumberWithUnit {
  double number;
  std::string unit;
};
std::optional<NumberWithUnit> split_number_with_unit(const std::string &text);

}  // namespace cascade
