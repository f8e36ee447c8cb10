#include "server/scenario/hyetograph.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <sstream>

namespace cascade {

namespace {

// The UTF-8 byte order mark that spreadsheet programs put at the start of a CSV
// file.
constexpr char kByteOrderMark[] = "\xEF\xBB\xBF";

std::string trim(const std::string &s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> cells_of(const std::string &line) {
  std::vector<std::string> cells;
  std::stringstream row(line);
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// A cell as a finite number, read as YAML reads numbers (as the case file's
// numbers are).
bool finite_number(const std::string &cell, double &value) {
  return YAML::convert<double>::decode(YAML::Node(cell), value) && std::isfinite(value);
}

}  // namespace

std::vector<cascade::v1::RainfallPoint> read_hyetograph(const std::string &csv_text, const CaseUnit &time_unit,
                                                        const CaseUnit &intensity_unit) {
  std::vector<cascade::v1::RainfallPoint> points;
  std::stringstream lines(csv_text);
  bool first_row = true;
  int line_number = 0;
  std::string previous_time;  // as written, for messages
  for (std::string line; std::getline(lines, line);) {
    ++line_number;
    if (line_number == 1 && line.rfind(kByteOrderMark, 0) == 0) line.erase(0, sizeof kByteOrderMark - 1);
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = cells_of(line);
    if (cells.size() != 2)
      throw HyetographError(line_number, "expected two cells, time and intensity, got " + std::to_string(cells.size()) +
                                             " ('" + line + "')");
    double time = 0, intensity = 0;
    const bool time_is_number = finite_number(cells[0], time);
    const bool intensity_is_number = finite_number(cells[1], intensity);
    const bool column_names = first_row && !time_is_number && !intensity_is_number;
    first_row = false;
    if (column_names) continue;
    if (!time_is_number || !intensity_is_number)
      throw HyetographError(line_number, "'" + (time_is_number ? cells[1] : cells[0]) + "' is not a finite number");
    if (time < 0) throw HyetographError(line_number, "the time must not be negative (is " + cells[0] + ")");
    if (intensity < 0) throw HyetographError(line_number, "the intensity must not be negative (is " + cells[1] + ")");
    cascade::v1::RainfallPoint point;
    point.set_time(time_unit.to_si(time));
    point.set_intensity(intensity_unit.to_si(intensity));
    if (!points.empty() && !(point.time() > points.back().time()))
      throw HyetographError(line_number,
                            "the time " + cells[0] + " is not later than the time before it (" + previous_time + ")");
    previous_time = cells[0];
    points.push_back(point);
  }
  if (points.empty()) throw HyetographError(0, "has no rows of time and intensity");
  return points;
}

}  // namespace cascade
