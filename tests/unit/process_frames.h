// The local frames (Engine::local_frame) of a run split over processes, made from a whole frame:
// every process holds every particle, in reverse id order (a share's order is not the id order),
// and the field "process" names each one's owner. Probes' and events' parts taken on these must
// combine to what the whole frame gives, whichever process owns a particle and whatever copies a
// process holds.
#pragma once

#include <cstddef>
#include <vector>

#include "server/core/field_frame.h"

namespace cascade {

inline std::vector<FieldFrame> frames_of_processes(const FieldFrame& whole, const std::vector<int>& owner,
                                                   int processes) {
  FieldFrame reversed = whole;
  const std::size_t n = whole.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = n - 1 - k;
    for (int a = 0; a < 3; ++a) reversed.position[3 * k + a] = whole.position[3 * i + a];
    reversed.phase[k] = whole.phase[i];
    reversed.id[k] = whole.id[i];
    if (!whole.free_surface.empty()) reversed.free_surface[k] = whole.free_surface[i];
    for (std::size_t f = 0; f < whole.fields.size(); ++f) {
      const int c = whole.fields[f].components;
      for (int m = 0; m < c; ++m) reversed.fields[f].values[c * k + m] = whole.fields[f].values[c * i + m];
    }
  }
  FieldFrame::RealField process{"process", "1", 1, std::vector<double>(n)};
  for (std::size_t k = 0; k < n; ++k) process.values[k] = owner[n - 1 - k];
  reversed.fields.push_back(process);
  return std::vector<FieldFrame>(std::size_t(processes), reversed);
}

}  // namespace cascade
