// Some particles' rows of an EngineState (engine_state.h), for a run split over processes
// (partition.h): a process's share of a checkpoint holds the rows of the particles it owns, and a
// share starts from the rows of the particles it will hold. An array's components are its size
// over the state's particle count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "server/core/engine_state.h"

namespace cascade {

// Components per particle of an array of a state with `particles` particles.
template <typename T>
std::size_t row_width(const std::vector<T>& values, std::size_t particles, const std::string& name) {
  if (particles == 0 && values.empty()) return 0;
  if (particles == 0 || values.size() % particles != 0)
    throw std::invalid_argument("the state's array '" + name + "' is not whole rows of its particles");
  return values.size() / particles;
}

// `state` with only the particles at `rows`, in that order; everything else as it is.
inline EngineState state_rows(const EngineState& state, const std::vector<std::size_t>& rows) {
  EngineState part = state;
  part.particles = rows.size();
  auto pick = [&](auto& arrays_out, const auto& arrays_in) {
    for (const auto& [name, values] : arrays_in) {
      const std::size_t c = row_width(values, state.particles, name);
      auto& out = arrays_out[name];
      out.clear();
      out.reserve(rows.size() * c);
      for (std::size_t k : rows) out.insert(out.end(), values.begin() + k * c, values.begin() + (k + 1) * c);
    }
  };
  pick(part.reals, state.reals);
  pick(part.integers, state.integers);
  return part;
}

// The rows of `state` in the order of its particles' ids (its "id" array), which must be
// 0 .. particles − 1 each once.
inline EngineState state_by_id(const EngineState& state) {
  const auto found = state.integers.find("id");
  if (found == state.integers.end() || found->second.size() != state.particles)
    throw std::invalid_argument("the state has no particle ids");
  std::vector<std::size_t> row_of(state.particles, state.particles);
  for (std::size_t k = 0; k < state.particles; ++k) {
    const std::uint32_t id = found->second[k];
    if (id >= state.particles || row_of[id] != state.particles)
      throw std::invalid_argument("the state's particle id " + std::to_string(id) + " is out of range or repeated");
    row_of[id] = k;
  }
  return state_rows(state, row_of);
}

}  // namespace cascade
