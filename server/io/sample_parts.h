// A sample of a run's outputs taken from each process's particles without gathering them (issue
// 17): the probes' parts (ProbeSampler::parts), the events' part (CascadeEventDetector::part) and
// the kinetic energy and fastest soil of the particles a process owns, as the bytes that
// Engine::parts_at_process_0 brings to process 0, where combine_sample_parts puts them together.
// One process takes the same path with one part. `cascade run`, the server's sessions and the
// other processes of a split server (split_server.cpp) take their parts with these functions.
#pragma once

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "server/core/field_frame.h"
#include "server/io/probe_sampler.h"
#include "server/scenario/cascade_events.h"

namespace cascade {

struct OutputSample {
  double kinetic_energy = 0;  // Σ ½ m |v|² of the water and soil (J, per metre in 2D)
  double max_soil_speed = 0;  // m/s
  std::vector<double> probe_values;  // with_probes only
  std::vector<CascadeEventDetector::Part> event_parts;  // with_probes only, one per process
};

// The request of a sample (Engine::parts_at_process_0): whether its parts hold the probes and
// events, or the energy alone. A split server's other processes take their parts by it.
inline std::vector<char> sample_request(bool with_probes) { return {char(with_probes ? 1 : 0)}; }
inline bool sample_request_with_probes(const std::vector<char>& request) {
  if (request.size() != 1)
    throw std::invalid_argument("a sample's request of " + std::to_string(request.size()) + " bytes, not 1");
  return request[0] != 0;
}

// The part of the rows `owned` marks of a process's local frame: [kinetic energy, fastest soil,
// the count of probe numbers, the probes' numbers, the events' numbers]; with_probes false leaves
// the probes and events out (a sample of the energy alone).
inline std::vector<char> sample_part(const ProbeSampler& probes, const CascadeEventDetector& events,
                                     double particle_mass, double ponding_pressure, bool with_probes,
                                     const FieldFrame& local, const std::vector<char>& owned) {
  const auto* velocity = local.find("velocity");
  double energy = 0, fastest_soil = 0;
  for (std::size_t i = 0; velocity && i < local.size(); ++i) {
    if (!owned[i] || local.phase[i] == 2) continue;  // the boundary's dummies do not move
    const double* v = &velocity->values[i * 3];
    const double v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    energy += 0.5 * particle_mass * v2;
    if (local.phase[i] == 1) fastest_soil = std::max(fastest_soil, std::sqrt(v2));
  }
  std::vector<double> numbers{energy, fastest_soil, 0.0};
  if (with_probes) {
    const std::vector<double> probe_numbers = ProbeSampler::flatten(probes.parts(local, &owned));
    numbers[2] = double(probe_numbers.size());
    numbers.insert(numbers.end(), probe_numbers.begin(), probe_numbers.end());
    const std::vector<double> event_numbers = CascadeEventDetector::flatten(events.part(local, ponding_pressure, &owned));
    numbers.insert(numbers.end(), event_numbers.begin(), event_numbers.end());
  }
  std::vector<char> bytes(numbers.size() * sizeof(double));
  std::memcpy(bytes.data(), numbers.data(), bytes.size());
  return bytes;
}

// The sample from every process's part (a part too short to be one throws std::runtime_error
// naming its process).
inline OutputSample combine_sample_parts(const ProbeSampler& probes, bool with_probes,
                                         const std::vector<std::vector<char>>& parts) {
  OutputSample sample;
  std::vector<std::vector<ProbeSampler::Part>> probe_parts;
  for (std::size_t r = 0; r < parts.size(); ++r) {
    std::vector<double> numbers(parts[r].size() / sizeof(double));
    std::memcpy(numbers.data(), parts[r].data(), numbers.size() * sizeof(double));
    if (numbers.size() < 3 || !(numbers[2] >= 0 && numbers[2] + 3 <= double(numbers.size())))
      throw std::runtime_error("process " + std::to_string(r) + " sent a malformed part of the outputs' sample");
    sample.kinetic_energy += numbers[0];
    sample.max_soil_speed = std::max(sample.max_soil_speed, numbers[1]);
    if (!with_probes) continue;
    const auto middle = numbers.begin() + 3 + std::ptrdiff_t(numbers[2]);
    probe_parts.push_back(ProbeSampler::unflatten(std::vector<double>(numbers.begin() + 3, middle)));
    sample.event_parts.push_back(CascadeEventDetector::unflatten(std::vector<double>(middle, numbers.end())));
  }
  if (with_probes) sample.probe_values = probes.combine(probe_parts);
  return sample;
}

}  // namespace cascade
