// Rows of the per-particle arrays, for a run split over processes (partition.h): some particles'
// values of every array copied into bytes and back. A message holds one block per array, in the
// order Simulation::for_each_particle_array lists them, each the rows' values one after another;
// every process lists the same arrays, so the blocks need no names. On the CPU the rows are copied
// straight between the arrays and the message, without a buffer of their own (a step exchanges
// several times); on a GPU they are gathered on the device and staged through the host (issue 17
// allows it for the CUDA backend).
#pragma once

#include <thrust/copy.h>
#include <thrust/gather.h>
#include <thrust/scatter.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "server/core/backend.h"
#include "server/core/types.h"

namespace cascade {

template <typename Backend>
struct ParticleRows {
  template <typename T>
  using Vector = typename Backend::template Vector<T>;
  static constexpr bool kHostMemory = std::is_same_v<Backend, OmpBackend>;

  // Appends the values of `array` at `rows` to `bytes`.
  template <typename T>
  static void pack(const Vector<T>& array, const Vector<std::uint32_t>& rows, std::vector<char>& bytes) {
    if constexpr (kHostMemory) {
      const std::size_t at = bytes.size();
      bytes.resize(at + rows.size() * sizeof(T));
      const T* values = thrust::raw_pointer_cast(array.data());
      const std::uint32_t* row = thrust::raw_pointer_cast(rows.data());
      for (std::size_t k = 0; k < rows.size(); ++k)  // the message's bytes need not be aligned for T
        std::memcpy(bytes.data() + at + k * sizeof(T), values + row[k], sizeof(T));
      return;
    }
    Vector<T> picked(rows.size());
    thrust::gather(Backend::policy(), rows.begin(), rows.end(), array.begin(), picked.begin());
    std::vector<T> host(picked.size());
    thrust::copy(picked.begin(), picked.end(), host.begin());
    const std::size_t at = bytes.size();
    bytes.resize(at + host.size() * sizeof(T));
    if (!host.empty()) std::memcpy(bytes.data() + at, host.data(), host.size() * sizeof(T));
  }

  // The next `count` values of type T in `bytes` from `offset`, which it advances.
  template <typename T>
  static std::vector<T> read(const std::vector<char>& bytes, std::size_t& offset, std::size_t count) {
    if (offset + count * sizeof(T) > bytes.size())
      throw std::runtime_error("a message between processes is shorter than the rows it announces");
    std::vector<T> values(count);
    if (count) std::memcpy(static_cast<void*>(values.data()), bytes.data() + offset, count * sizeof(T));
    offset += count * sizeof(T);
    return values;
  }

  // array[rows[k]] = values[k].
  template <typename T>
  static void scatter(Vector<T>& array, const Vector<std::uint32_t>& rows, const std::vector<T>& values) {
    const Vector<T> staged(values.begin(), values.end());
    thrust::scatter(Backend::policy(), staged.begin(), staged.end(), rows.begin(), array.begin());
  }

  // array[rows[k]] = the next rows.size() values of type T in `bytes` from `offset`, which it
  // advances: what pack wrote.
  template <typename T>
  static void unpack(Vector<T>& array, const Vector<std::uint32_t>& rows, const std::vector<char>& bytes,
                     std::size_t& offset) {
    if constexpr (kHostMemory) {
      if (offset + rows.size() * sizeof(T) > bytes.size())
        throw std::runtime_error("a message between processes is shorter than the rows it announces");
      T* values = thrust::raw_pointer_cast(array.data());
      const std::uint32_t* row = thrust::raw_pointer_cast(rows.data());
      for (std::size_t k = 0; k < rows.size(); ++k)
        std::memcpy(static_cast<void*>(values + row[k]), bytes.data() + offset + k * sizeof(T), sizeof(T));
      offset += rows.size() * sizeof(T);
      return;
    }
    scatter(array, rows, read<T>(bytes, offset, rows.size()));
  }

  // Keeps the rows `rows` of `array`, in that order, and appends `values` after them.
  template <typename T>
  static void keep_and_append(Vector<T>& array, const Vector<std::uint32_t>& rows, const std::vector<T>& values) {
    Vector<T> kept(rows.size() + values.size());
    thrust::gather(Backend::policy(), rows.begin(), rows.end(), array.begin(), kept.begin());
    thrust::copy(values.begin(), values.end(), kept.begin() + rows.size());
    array.swap(kept);
  }
};

// The step limit of the particles this process owns (Eq. 40), the largest Real for the copies of
// other processes' particles, which their owners limit.
template <typename Real>
struct OwnedStepLimit {
  const Real* step_limit;
  const std::uint32_t* owner;
  std::uint32_t process;
  CASCADE_HD Real operator()(std::uint32_t i) const {
    return owner[i] == process ? step_limit[i] : std::numeric_limits<Real>::max();
  }
};

// A reduction's term of a particle this process owns, the reduction's identity for the others
// (copies, whose owners count them).
template <typename F, typename T>
struct OwnedTerm {
  F term;
  const std::uint32_t* owner;
  std::uint32_t process;
  T identity;
  CASCADE_HD T operator()(std::uint32_t i) const { return owner[i] == process ? term(i) : identity; }
};

// The entries of a particle's neighbour list: the work of its interaction passes (LoadBalance).
struct ListLength {
  const std::uint32_t* count;
  CASCADE_HD std::uint64_t operator()(std::uint32_t i) const { return count[i]; }
};

// Runs `pass` on the particles this process owns only (Simulation::launch_owned).
template <typename F>
struct OwnedOnly {
  F pass;
  const std::uint32_t* owner;
  std::uint32_t process;
  CASCADE_HD void operator()(std::uint32_t i) const {
    if (owner[i] == process) pass(i);
  }
};

// A copy of another process's particle.
struct OwnedElsewhere {
  std::uint32_t process;
  CASCADE_HD bool operator()(std::uint32_t owner) const { return owner != process; }
};

}  // namespace cascade
