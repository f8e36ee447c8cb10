#include "server/parallel/state_message.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace cascade {
namespace {

class Writer {
 public:
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* bytes = reinterpret_cast<const char*>(&v);
    out.insert(out.end(), bytes, bytes + sizeof v);
  }
  template <typename T>
  void values(const std::vector<T>& v) {
    value(std::uint64_t(v.size()));
    const char* bytes = reinterpret_cast<const char*>(v.data());
    out.insert(out.end(), bytes, bytes + v.size() * sizeof(T));
  }
  void text(const std::string& s) { values(std::vector<char>(s.begin(), s.end())); }
  std::vector<char> out;
};

class Reader {
 public:
  explicit Reader(const std::vector<char>& in) : in_(in) {}
  template <typename T>
  T value() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  template <typename T>
  std::vector<T> values() {
    const auto n = value<std::uint64_t>();
    if (n > (in_.size() - at_) / sizeof(T)) throw std::invalid_argument("a state message ends early");
    std::vector<T> v(n);
    take(v.data(), n * sizeof(T));
    return v;
  }
  std::string text() {
    const auto chars = values<char>();
    return std::string(chars.begin(), chars.end());
  }
  bool done() const { return at_ == in_.size(); }

 private:
  void take(void* to, std::size_t bytes) {
    if (bytes > in_.size() - at_) throw std::invalid_argument("a state message ends early");
    if (bytes) std::memcpy(to, in_.data() + at_, bytes);
    at_ += bytes;
  }
  const std::vector<char>& in_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<char> state_message(const EngineState& s) {
  Writer w;
  w.value(std::int32_t(s.dimensions));
  w.value(std::uint8_t(s.single_precision));
  w.value(std::uint64_t(s.particles));
  w.value(s.time), w.value(s.last_dt), w.value(s.steps);
  w.value(s.forcing);
  w.value(std::uint64_t(s.reals.size()));
  for (const auto& [name, values] : s.reals) w.text(name), w.values(values);
  w.value(std::uint64_t(s.integers.size()));
  for (const auto& [name, values] : s.integers) w.text(name), w.values(values);
  w.values(s.displacement_reference);
  w.value(std::int32_t(s.stage));
  w.value(std::uint64_t(s.stage_values.size()));
  for (const auto& [name, value] : s.stage_values) w.text(name), w.value(value);
  w.value(s.pore_water);
  return std::move(w.out);
}

EngineState state_from_message(const std::vector<char>& message) {
  Reader r(message);
  EngineState s;
  s.dimensions = r.value<std::int32_t>();
  s.single_precision = r.value<std::uint8_t>() != 0;
  s.particles = std::size_t(r.value<std::uint64_t>());
  s.time = r.value<double>(), s.last_dt = r.value<double>(), s.steps = r.value<std::uint64_t>();
  s.forcing = r.value<HydraulicForcing>();
  for (auto n = r.value<std::uint64_t>(); n > 0; --n) {
    const std::string name = r.text();
    s.reals[name] = r.values<double>();
  }
  for (auto n = r.value<std::uint64_t>(); n > 0; --n) {
    const std::string name = r.text();
    s.integers[name] = r.values<std::uint32_t>();
  }
  s.displacement_reference = r.values<double>();
  s.stage = r.value<std::int32_t>();
  for (auto n = r.value<std::uint64_t>(); n > 0; --n) {
    const std::string name = r.text();
    s.stage_values[name] = r.value<double>();
  }
  s.pore_water = r.value<PoreWaterAccount>();
  if (!r.done()) throw std::invalid_argument("a state message runs on past its state");
  return s;
}

}  // namespace cascade
