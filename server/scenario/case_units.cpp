#include "server/scenario/case_units.h"

#include <yaml-cpp/yaml.h>

#include "cascade/v1/units.pb.h"

namespace cascade {

namespace {

// Every unit a case file may write, grouped by dimension, the SI unit first.
// The factors are exact: a multiplier or a divisor that is a whole number.
const CaseUnit kUnits[] = {
    {"s", "s", 1, 1},           {"min", "s", 60, 1},     {"h", "s", 3600, 1},        {"day", "s", 86400, 1},
    {"d", "s", 86400, 1},       {"m/s", "m/s", 1, 1},    {"mm/h", "m/s", 1, 3.6e6},  {"mm/day", "m/s", 1, 8.64e7},
    {"cm/h", "m/s", 1, 3.6e5},  {"m/h", "m/s", 1, 3600}, {"m/day", "m/s", 1, 86400}, {"Pa", "Pa", 1, 1},
    {"kPa", "Pa", 1e3, 1},      {"MPa", "Pa", 1e6, 1},   {"GPa", "Pa", 1e9, 1},      {"m", "m", 1, 1},
    {"cm", "m", 1, 100},        {"mm", "m", 1, 1000},    {"km", "m", 1e3, 1},        {"m/s^2", "m/s^2", 1, 1},
    {"kg/m^3", "kg/m^3", 1, 1}, {"1/m", "1/m", 1, 1},
};

struct Dimension {
  const char *si;
  const char *name;
};

const Dimension kDimensions[] = {
    {"s", "a time"},
    {"m/s", "a speed"},
    {"Pa", "a pressure"},
    {"m", "a length"},
    {"m/s^2", "an acceleration"},
    {"kg/m^3", "a density"},
    {"1/m", "an inverse length"},
};

}  // namespace

const CaseUnit *find_case_unit(const std::string &name) {
  for (const CaseUnit &unit : kUnits)
    if (name == unit.name) return &unit;
  return nullptr;
}

std::string si_unit_of(const google::protobuf::FieldDescriptor *field) {
  return field->options().GetExtension(cascade::v1::unit);
}

std::string dimension_name(const std::string &si) {
  for (const Dimension &d : kDimensions)
    if (si == d.si) return d.name;
  return {};
}

std::string unit_names(const std::string &si) {
  std::string names;
  for (const CaseUnit &unit : kUnits)
    if (si == unit.si) names += (names.empty() ? "" : ", ") + std::string(unit.name);
  return names;
}

std::string unit_problem(const std::string &name, const std::string &si) {
  const CaseUnit *unit = find_case_unit(name);
  if (unit == nullptr)
    return "unknown unit '" + name + "' (units of " + dimension_name(si) + ": " + unit_names(si) + ")";
  if (si != unit->si)
    return "takes " + dimension_name(si) + " (" + si + "); '" + name + "' is " + dimension_name(unit->si);
  return {};
}

std::optional<NumberWithUnit> split_number_with_unit(const std::string &text) {
  const auto number_end = text.find(' ');
  if (number_end == std::string::npos || number_end == 0) return std::nullopt;
  const auto unit_start = text.find_first_not_of(' ', number_end);
  if (unit_start == std::string::npos) return std::nullopt;
  const std::string unit = text.substr(unit_start, text.find_last_not_of(' ') + 1 - unit_start);
  double number = 0;
  if (!YAML::convert<double>::decode(YAML::Node(text.substr(0, number_end)), number)) return std::nullopt;
  return NumberWithUnit{number, unit};
}

}  // namespace cascade
