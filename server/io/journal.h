// A simulation's journal (journal.jsonl): every applied command as one JSON line of
// cascade.v1.JournalEntry, flushed to the disk before the command's reply goes out, so that the
// file always holds what clients were told. `cascade run CASE --replay JOURNAL` reads it back.
#pragma once

#include <cstdio>
#include <filesystem>
#include <vector>

#include "cascade/v1/journal.pb.h"

namespace cascade {

class JournalWriter {
 public:
  // Opens `path` for appending (creates it). Throws std::runtime_error if it cannot.
  explicit JournalWriter(const std::filesystem::path& path);
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;

  // Appends the entry and syncs the file. Throws std::runtime_error on a write error.
  void append(const v1::JournalEntry& entry);
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
};

// All entries of a journal file, in order. Throws std::runtime_error naming the file and line when
// the file cannot be read or a line is not a JournalEntry.
std::vector<v1::JournalEntry> read_journal(const std::filesystem::path& path);

}  // namespace cascade
