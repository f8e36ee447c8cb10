// libFuzzer target: the case loader on any text (what CreateSimulation's case_yaml and `cascade
// run` read). Every input either loads to a valid spec or is refused with a CaseError, which names
// the key and line; any other exception, a crash, a sanitizer report, a leak or a hang is a finding
// (scripts/fuzz.sh).
#include <cstddef>
#include <cstdint>
#include <string>

#include "server/scenario/case_error.h"
#include "server/scenario/case_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    cascade::load_case_text(text);
  } catch (const cascade::CaseError&) {
  }
  return 0;
}
