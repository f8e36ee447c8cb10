// run.json: what a finished (or failed) run reports about itself, for people and for scripts
// that compare runs. Keys and units in docs/output.md.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "server/core/partition.h"

namespace cascade {

struct RunEvent {
  double time = 0.0;  // simulated time (s)
  std::uint64_t step = 0;
  std::string kind;    // e.g. "steer", "checkpoint", "particles_lost"
  std::string detail;  // free text
};

struct RunSummary {
  enum class Status { completed, failed };

  std::string case_name;
  Status status = Status::completed;
  std::string error;                 // written only when status is failed
  std::string precision = "double";  // "float" or "double"
  double sim_time = 0.0;             // simulated time reached (s)
  std::uint64_t steps = 0;
  double wall_seconds = 0.0;
  struct Particles {
    std::uint64_t total = 0, water = 0, soil = 0, boundary = 0;
  } particles;
  double particle_steps_per_second = 0.0;  // particles × steps / wall_seconds
  double bytes_per_particle = 0.0;         // device memory of the particle arrays / total
  int processes = 1;                       // a run split over processes (mpirun): how many,
  std::vector<std::uint64_t> process_particles;  // and the particles each held at the end,
  // The frames written (fields.h5, VTK, snapshots) and the wall time of the outputs: taking the
  // frames (split over processes, gathering them to process 0) and the probes, and writing them.
  std::uint64_t frames_written = 0;
  double output_seconds = 0;
  double exchange_seconds = 0;    // the wall time of the steps' exchanges (the slowest process's),
  std::uint64_t exchange_bytes = 0;  // and the bytes all processes sent in them
  // How evenly they shared the work (LoadBalance, server/core/partition.h), over the list
  // rebuilds; every rebuild's figure is in balance.csv.
  struct Balance {
    double last = 1, mean = 1, largest = 1;
    std::uint64_t rebuilds = 0, repartitions = 0;
  } balance;
  std::uint64_t lost_particles = 0;        // particles that left the domain
  // The pore water that entered the soil through each boundary (Engine::pore_water_account; m³,
  // m² per metre of depth in 2D), written only for a case with soil.
  struct PoreWater {
    bool present = false;
    double rain = 0, walls = 0, surface = 0;
  } pore_water;
  // The case's terrain (ScenarioSpec.terrain): its local frame is x = X − origin[0],
  // y = Y − origin[1] in the rasters' map coordinates, z the elevation.
  struct Terrain {
    bool present = false;
    double origin[2] = {0.0, 0.0};
    std::string crs;                            // WKT
    std::string surface, base;                  // the rasters (or the thickness) it came from
    std::vector<std::array<double, 2>> section;  // 2D: the section's polyline in map coordinates
  } terrain;
  std::vector<RunEvent> events;
};

// The summary as a JSON object (UTF-8, two-space indent). Non-finite numbers become null;
// invalid UTF-8 in strings becomes U+FFFD.
std::string run_summary_json(const RunSummary& summary);

// Writes run_summary_json(summary) to `path` atomically (temporary file, then rename).
void write_run_json(const std::filesystem::path& path, const RunSummary& summary);

// A split run's balance.csv: per list rebuild the step, the time, the imbalance (the most work of a
// process over the mean, measured after the rebuild) and whether the slabs were cut again there.
void write_balance_csv(const std::filesystem::path& path, const LoadBalance& balance);

}  // namespace cascade
