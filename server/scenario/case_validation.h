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

}  // namespace cascade
