#include "server/io/journal.h"

#include <google/protobuf/util/json_util.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

namespace cascade {

JournalWriter::JournalWriter(const std::filesystem::path& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "a");
  if (!file_) throw std::runtime_error("cannot open journal " + path.string() + ": " + std::strerror(errno));
}

JournalWriter::~JournalWriter() {
  if (file_) std::fclose(file_);
}

void JournalWriter::append(const v1::JournalEntry& entry) {
  std::string line;
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  const auto status = google::protobuf::util::MessageToJsonString(entry, &line, options);
  if (!status.ok()) throw std::runtime_error("journal entry not serialisable: " + status.ToString());
  line += '\n';
  // fsync: the reply to the command goes out after this returns, and must not promise more than
  // the disk holds should the server die next.
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0 ||
      ::fsync(::fileno(file_)) != 0)
    throw std::runtime_error("cannot write journal " + path_.string() + ": " + std::strerror(errno));
}

std::vector<v1::JournalEntry> read_journal(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open journal " + path.string());
  std::vector<v1::JournalEntry> entries;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    v1::JournalEntry entry;
    const auto status = google::protobuf::util::JsonStringToMessage(line, &entry);
    if (!status.ok())
      throw std::runtime_error(path.string() + ":" + std::to_string(number) + ": not a journal entry: " +
                               std::string(status.message()));
    entries.push_back(std::move(entry));
  }
  return entries;
}

}  // namespace cascade
