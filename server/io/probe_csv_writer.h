// probes.csv: one row per sampling time, one column per probe, flushed row by row so the file
// can be plotted while the run goes on (docs/output.md).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace cascade {

class ProbeCsvWriter {
 public:
  // Creates (or truncates) `path` and writes the header "time,<name1>,<name2>,...". Names that
  // contain a comma, quote or line break are quoted as RFC 4180 says. Throws std::runtime_error
  // if the file cannot be created and std::invalid_argument for an empty name.
  ProbeCsvWriter(const std::filesystem::path& path, std::vector<std::string> probe_names);
  ~ProbeCsvWriter();
  ProbeCsvWriter(const ProbeCsvWriter&) = delete;
  ProbeCsvWriter& operator=(const ProbeCsvWriter&) = delete;

  // One row: the time (s) and one value per probe, in the order of the names. Values are
  // written in the shortest form that reads back to the same double; NaN as "nan".
  void write_row(double time, const std::vector<double>& values);

  void close();
  const std::vector<std::string>& probe_names() const { return names_; }

 private:
  void put(const std::string& text);

  std::filesystem::path path_;
  std::vector<std::string> names_;
  std::FILE* file_ = nullptr;
};

}  // namespace cascade
