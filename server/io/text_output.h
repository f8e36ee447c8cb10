// Small text helpers shared by the writers of docs/output.md: numbers that read back exactly,
// XML escaping and whole-file atomic replacement (index files are rewritten after every frame,
// so a reader or a killed run never sees a half-written one).
#pragma once

#include <filesystem>
#include <string>

namespace cascade {

// Shortest text that parses back to the same double ("0.1", "1e-05", "nan", "inf", "-inf").
std::string format_double(double value);

// Escapes &, <, >, " and ' for use in XML attribute values and text.
std::string xml_escape(const std::string& text);

// Writes `contents` to `path` through a temporary file in the same directory and a rename, so
// `path` always holds either the old or the new contents. Throws std::runtime_error on failure.
void write_file_atomically(const std::filesystem::path& path, const std::string& contents);

}  // namespace cascade
