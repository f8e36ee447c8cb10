#include "server/io/probe_csv_writer.h"

#include <stdexcept>
#include <utility>

#include "server/io/text_output.h"

namespace cascade {
namespace {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace

ProbeCsvWriter::ProbeCsvWriter(const std::filesystem::path& path,
                               std::vector<std::string> probe_names)
    : path_(path), names_(std::move(probe_names)) {
  std::string header = "time";
  for (const std::string& name : names_) {
    if (name.empty()) throw std::invalid_argument("probe names must not be empty");
    header += "," + csv_field(name);
  }
  if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path());
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) throw std::runtime_error("cannot create " + path_.string());
  put(header + "\n");
}

ProbeCsvWriter::~ProbeCsvWriter() {
  if (file_) std::fclose(file_);
}

void ProbeCsvWriter::close() {
  if (!file_) return;
  const int status = std::fclose(file_);
  file_ = nullptr;
  if (status != 0) throw std::runtime_error("cannot close " + path_.string());
}

void ProbeCsvWriter::write_row(double time, const std::vector<double>& values) {
  if (values.size() != names_.size())
    throw std::invalid_argument("probe row has " + std::to_string(values.size()) + " values for " +
                                std::to_string(names_.size()) + " probes");
  std::string row = format_double(time);
  for (const double value : values) row += "," + format_double(value);
  put(row + "\n");
}

void ProbeCsvWriter::put(const std::string& text) {
  if (!file_) throw std::logic_error("write to closed " + path_.string());
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0)
    throw std::runtime_error("cannot write " + path_.string());
}

}  // namespace cascade
