// Case files: YAML → cascade.v1.ScenarioSpec.
//
// The YAML layout is the proto message tree: keys are the proto field names, nested as in the
// proto; a oneof appears as one key naming its case (`shape: {box: {min: [..], max: [..]}}`,
// `{name: water, water: {density: 1000}}`); enums are their value names in lowercase
// (`kind: fluid`, `kind: front`); a Point2 is an `[x, z]` pair. A double field whose schema names
// its SI unit (the `unit` option, units.proto) may be written "<number> <unit>" (`end_time: 36 h`,
// also inside lists: `min: [0 m, 50 cm]`) and is converted to SI (case_units.h); a field without
// one is a plain number. A `hydraulics.hyetograph` is read from its CSV file (hyetograph.h) into
// the `rainfall` series. Every problem — YAML syntax,
// unknown or duplicated keys, wrong types, wrong vector lengths, impossible values — raises a
// CaseError naming the key as a dotted path (`bodies[1].shape.box.min`) and its line in the file.
#pragma once

#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/scenario/case_error.h"

namespace cascade {

// One `--set path.to.key=value` from the command line. The value is YAML: a scalar or a flow
// sequence or mapping (`dp=0.02`, `bodies[0].shape.box.max=[0.1, 0.2]`).
struct CaseOverride {
  std::string key;
  std::string value;
};

// Parses "a.b[2].c=1.5"; throws CaseError (key "--set") when the text is not of that form.
CaseOverride parse_override(const std::string& text);

// Reads a case file, applies the overrides to its YAML tree, maps the tree onto a ScenarioSpec,
// expands its hyetograph (a CSV file relative to the case file's folder) into `rainfall`,
// validates it (validate_spec) and fills in the defaults (apply_defaults). An empty `name` becomes
// the file's stem.
cascade::v1::ScenarioSpec load_case_file(const std::string& path, const std::vector<CaseOverride>& overrides = {});

// As load_case_file, from text; `file_name` only labels the errors. Text has no folder to read
// files from: a hyetograph in it is an error (the server loads case text sent to it this way and
// reads no files that a request names).
cascade::v1::ScenarioSpec load_case_text(const std::string& yaml_text, const std::vector<CaseOverride>& overrides = {},
                                         const std::string& file_name = "<case>");

// The semantic checks, for any spec (one that came over gRPC as well as one from a file). Fields
// whose proto comment says "0 means <default>" may be 0. Errors name the key as a dotted path and
// have line -1.
void validate_spec(const cascade::v1::ScenarioSpec& spec);

// Replaces the "0 / unset means <default>" fields that have a fixed default with that default:
// h_over_dp 1.3, numerics.cfl 0.2, numerics.min_dt 1e-12, output.interval end_time / 100,
// output.hdf5 true, water density 1000, δ 0.1, α_μ,w 0.01, probe phase "water"; for soils K_w 2e6,
// c_pw0 10 K_sat, δ 0.1, α_μ,s 0.1, s_max 1, residual cohesion and friction angle = the peak ones,
// p_atm 101e3. Defaults that need the geometry or another section (sound speed, max speed, max
// pressure, boundary layers, K0) stay 0 for the solver.
void apply_defaults(cascade::v1::ScenarioSpec& spec);

}  // namespace cascade
