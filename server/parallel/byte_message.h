// Values of trivially copyable types as bytes and back: the messages the processes of a split run
// send each other (frames, checkpoint states, sizes). Sender and receiver agree on the layout; a
// reader that runs past its message throws.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace cascade {

class ByteWriter {
 public:
  template <typename T>
  void put(const T* values, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::size_t at = bytes.size();
    bytes.resize(at + count * sizeof(T));
    if (count) std::memcpy(bytes.data() + at, values, count * sizeof(T));
  }
  template <typename T>
  void put(const T& value) {
    put(&value, 1);
  }
  // Its length, then its values.
  template <typename T>
  void put_vector(const std::vector<T>& values) {
    put(std::uint64_t(values.size()));
    put(values.data(), values.size());
  }
  void put_text(const std::string& text) { put_vector(std::vector<char>(text.begin(), text.end())); }

  std::vector<char> bytes;
};

class ByteReader {
 public:
  explicit ByteReader(const std::vector<char>& bytes) : bytes_(bytes) {}
  template <typename T>
  void take(T* values, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (count > (bytes_.size() - at_) / sizeof(T)) throw std::invalid_argument("a message between processes ends early");
    if (count) std::memcpy(values, bytes_.data() + at_, count * sizeof(T));
    at_ += count * sizeof(T);
  }
  template <typename T>
  T take() {
    T value;
    take(&value, 1);
    return value;
  }
  template <typename T>
  std::vector<T> take_vector() {
    const auto count = take<std::uint64_t>();
    if (count > (bytes_.size() - at_) / sizeof(T)) throw std::invalid_argument("a message between processes ends early");
    std::vector<T> values(count);
    take(values.data(), values.size());
    return values;
  }
  std::string take_text() {
    const auto chars = take_vector<char>();
    return std::string(chars.begin(), chars.end());
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  const std::vector<char>& bytes_;
  std::size_t at_ = 0;
};

}  // namespace cascade
