#include "server/parallel/state_message.h"

#include <cstdint>
#include <stdexcept>
#include <string>

#include "server/parallel/byte_message.h"

namespace cascade {
std::vector<char> state_message(const EngineState& s) {
  ByteWriter w;
  w.put(std::int32_t(s.dimensions));
  w.put(std::uint8_t(s.single_precision));
  w.put(std::uint64_t(s.particles));
  w.put(s.time), w.put(s.last_dt), w.put(s.steps);
  w.put(s.forcing);
  w.put(std::uint64_t(s.reals.size()));
  for (const auto& [name, values] : s.reals) w.put_text(name), w.put_vector(values);
  w.put(std::uint64_t(s.integers.size()));
  for (const auto& [name, values] : s.integers) w.put_text(name), w.put_vector(values);
  w.put_vector(s.displacement_reference);
  w.put(std::int32_t(s.stage));
  w.put(std::uint64_t(s.stage_values.size()));
  for (const auto& [name, value] : s.stage_values) w.put_text(name), w.put(value);
  w.put(s.pore_water);
  return std::move(w.bytes);
}

EngineState state_from_message(const std::vector<char>& message) {
  ByteReader r(message);
  EngineState s;
  s.dimensions = r.take<std::int32_t>();
  s.single_precision = r.take<std::uint8_t>() != 0;
  s.particles = std::size_t(r.take<std::uint64_t>());
  s.time = r.take<double>(), s.last_dt = r.take<double>(), s.steps = r.take<std::uint64_t>();
  s.forcing = r.take<HydraulicForcing>();
  for (auto n = r.take<std::uint64_t>(); n > 0; --n) {
    const std::string name = r.take_text();
    s.reals[name] = r.take_vector<double>();
  }
  for (auto n = r.take<std::uint64_t>(); n > 0; --n) {
    const std::string name = r.take_text();
    s.integers[name] = r.take_vector<std::uint32_t>();
  }
  s.displacement_reference = r.take_vector<double>();
  s.stage = r.take<std::int32_t>();
  for (auto n = r.take<std::uint64_t>(); n > 0; --n) {
    const std::string name = r.take_text();
    s.stage_values[name] = r.take<double>();
  }
  s.pore_water = r.take<PoreWaterAccount>();
  if (!r.done()) throw std::invalid_argument("a state message runs on past its state");
  return s;
}

}  // namespace cascade
