// libFuzzer target: a ScenarioSpec as CreateSimulation receives it (protobuf bytes). A spec that
// parses is either refused by validate_spec with a CaseError naming the field or passes it and
// takes its defaults; any other exception, a crash or a sanitizer report is a finding
// (scripts/fuzz.sh; seeds: the case files, converted by fuzz_seed_specs).
#include <cstddef>
#include <cstdint>

#include "cascade/v1/scenario.pb.h"
#include "server/scenario/case_error.h"
#include "server/scenario/case_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cascade::v1::ScenarioSpec spec;
  if (!spec.ParseFromArray(data, static_cast<int>(size))) return 0;
  try {
    cascade::validate_spec(spec);
    cascade::apply_defaults(spec);
  } catch (const cascade::CaseError&) {
  }
  return 0;
}
