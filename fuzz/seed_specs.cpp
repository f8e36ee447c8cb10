// The seed corpus of fuzz_scenario_spec: each case file given, loaded as `cascade run` loads it,
// written as the binary ScenarioSpec that CreateSimulation would receive.
//
// usage: fuzz_seed_specs OUT_DIR CASE.yaml...
#include <filesystem>
#include <fstream>
#include <iostream>

#include "server/scenario/case_error.h"
#include "server/scenario/case_loader.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: fuzz_seed_specs OUT_DIR CASE.yaml...\n";
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::filesystem::create_directories(out);
  for (int k = 2; k < argc; ++k) {
    const std::filesystem::path case_file = argv[k];
    try {
      const auto spec = cascade::load_case_file(case_file.string());
      std::ofstream(out / (case_file.stem().string() + ".pb"), std::ios::binary) << spec.SerializeAsString();
    } catch (const cascade::CaseError& e) {
      std::cerr << "fuzz_seed_specs: " << e.what() << "\n";
      return 1;
    }
  }
  return 0;
}
