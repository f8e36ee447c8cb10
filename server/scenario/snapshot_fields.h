// The fields a snapshot (output.snapshots) can be coloured by, as the engine's frames name them
// (server/core/simulation.h): shared by the case checks and the snapshot writer.
#pragma once

#include <set>
#include <string>

namespace cascade {

// Fields of every phase, and fields the frame has for soil particles only (cases with soil).
inline const std::set<std::string> kSnapshotFields = {"phase",      "pressure",   "density",   "velocity",
                                                      "velocity_x", "velocity_y", "velocity_z"};
inline const std::set<std::string> kSoilSnapshotFields = {
    "pore_pressure", "saturation",        "porosity",          "plastic_strain",    "seepage",
    "seepage_x",     "seepage_y",         "seepage_z",         "displacement",      "displacement_x",
    "displacement_y", "displacement_z",   "stress_xx",         "stress_yy",         "stress_zz",
    "stress_xy",     "stress_yz",         "stress_zx",         "effective_stress_xx", "effective_stress_yy",
    "effective_stress_zz", "effective_stress_xy", "effective_stress_yz", "effective_stress_zx"};

inline bool is_soil_snapshot_field(const std::string& field) { return kSoilSnapshotFields.count(field) > 0; }

// Fields whose sign matters (suction below zero, compression below zero): drawn with the
// diverging map unless the case says otherwise.
inline bool is_signed_snapshot_field(const std::string& field) {
  return field == "pore_pressure" || field.rfind("stress_", 0) == 0 || field.rfind("effective_stress_", 0) == 0;
}

}  // namespace cascade
