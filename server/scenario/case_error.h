// The error every case-file problem raises: it names the key (a dotted path such as
// `bodies[1].shape.box.min`) and, when known, the line and column in the case file.
#pragma once

#include <stdexcept>
#include <string>

namespace cascade {

class CaseError : public std::runtime_error {
 public:
  CaseError(std::string key, std::string message, int line = -1, int column = -1, std::string file = {})
      : std::runtime_error(format(file, key, message, line, column)),
        key_(std::move(key)),
        message_(std::move(message)),
        line_(line) {}

  const std::string& key() const { return key_; }
  const std::string& message() const { return message_; }  // without file, line and key
  int line() const { return line_; }  // 1-based; -1 when the key has no place in a file

 private:
  static std::string format(const std::string& file, const std::string& key, const std::string& message,
                            int line, int column) {
    std::string where = file.empty() ? std::string() : file + ":";
    if (line > 0) where += std::to_string(line) + ":" + std::to_string(column > 0 ? column : 1) + ": ";
    else if (!where.empty()) where += " ";
    return where + "key '" + key + "': " + message;
  }

  std::string key_;
  std::string message_;
  int line_;
};

}  // namespace cascade
