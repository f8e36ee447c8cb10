// The semantic checks of a ScenarioSpec, with a caller-supplied way to report a failure. The case
// loader reports with the key's line in the file; validate_spec (case_loader.h) without one.
#pragma once

#include <functional>
#include <string>

#include "cascade/v1/scenario.pb.h"

namespace cascade {

// Called with the dotted key and the message of the first problem found; must throw.
using CaseFailure = std::function<void(const std::string& key, const std::string& message)>;

void check_spec(const cascade::v1::ScenarioSpec& spec, const CaseFailure& fail);

// The checks of one output.snapshots entry, for a snapshot of `spec`'s simulation asked for
// outside the case (the snapshot RPCs); `key` prefixes the keys reported.
void check_snapshot(const cascade::v1::ScenarioSpec& spec, const std::string& key, const cascade::v1::Snapshot& snapshot,
                    const CaseFailure& fail);

// The defaults of a checked snapshot (docs/rendering.md): field phase, name = field, camera side
// in 2D and orbit in 3D, colour map by the field's sign, 1280 × 720.
void apply_snapshot_defaults(cascade::v1::Snapshot& snapshot, int dimensions);

}  // namespace cascade
