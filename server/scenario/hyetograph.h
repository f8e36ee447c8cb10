// A hyetograph CSV (HydraulicBoundary.hyetograph, docs/cases.md): two columns,
// time and intensity, in the units the case names; a first row of column names,
// blank lines and lines starting with # are skipped. Read into the `rainfall`
// series in SI.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/scenario/case_units.h"

namespace cascade {

// A problem of the CSV text at `line` (1-based); the case loader adds the key
// and the file.
class HyetographError : public std::runtime_error {
 public:
  HyetographError(int line, const std::string &message) : std::runtime_error(message), line_(line) {}
  int line() const { return line_; }  // 0 for the file as a whole (no rows)

 private:
  int line_;
};

// The rows as RainfallPoints in s and m/s. Times strictly increasing and >= 0,
// intensities >= 0, at least one row; otherwise HyetographError.
std::vector<cascade::v1::RainfallPoint> read_hyetograph(const std::string &csv_text, const CaseUnit &time_unit,
                                                        const CaseUnit &intensity_unit);

}  // namespace cascade
