// Case files → ScenarioSpec: the shipped cases load with their defaults, overrides apply, and every
// kind of mistake is a CaseError that names the key and its line.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"
#include "server/scenario/soil_setup.h"

namespace cascade {
namespace {

namespace pb = cascade::v1;

const std::string kCases = std::string(CASCADE_SOURCE_DIR) + "/cases/";
const std::string kBadCases = std::string(CASCADE_SOURCE_DIR) + "/tests/unit/bad_cases/";

// A small valid 2D case; the tests below break it one line at a time (line numbers are 1-based).
const std::vector<std::string> kBase = {
    "dimensions: 2",                                                      // 1
    "dp: 0.02",                                                           // 2
    "h_over_dp: 1.3",                                                     // 3
    "end_time: 1.0",                                                      // 4
    "domain:",                                                            // 5
    "  min: [-0.2, -0.2]",                                                // 6
    "  max: [1.2, 1.0]",                                                  // 7
    "gravity: [0, -9.81]",                                                // 8
    "materials:",                                                         // 9
    "  - name: water",                                                    // 10
    "    water: {density: 1000}",                                         // 11
    "bodies:",                                                            // 12
    "  - name: tank",                                                     // 13
    "    kind: boundary",                                                 // 14
    "    shape: {box: {min: [-0.1, -0.1], max: [1.1, 0.6]}}",             // 15
    "    subtract:",                                                      // 16
    "      - box: {min: [0, 0], max: [1, 0.9]}",                          // 17
    "  - name: water",                                                    // 18
    "    kind: fluid",                                                    // 19
    "    material: water",                                                // 20
    "    shape: {box: {min: [0, 0], max: [1, 0.5]}}",                     // 21
    "    initial: {hydrostatic: true}",                                   // 22
    "probes:",                                                            // 23
    "  - {name: p, kind: point, field: pressure, position: [0.5, 0.1]}",  // 24
    "  - {name: front, kind: front, axis: x}",                            // 25
};

std::string join(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

std::string base() { return join(kBase); }

// The base case with line `n` replaced by `text` (which may hold several lines).
std::string with_line(int n, const std::string& text) {
  std::vector<std::string> lines = kBase;
  lines.at(n - 1) = text;
  return join(lines);
}

// The base case without lines first..last.
std::string without_lines(int first, int last) {
  std::vector<std::string> lines = kBase;
  lines.erase(lines.begin() + first - 1, lines.begin() + last);
  return join(lines);
}

struct Expected {
  std::string key;
  int line;             // -1: no place in the file
  std::string message;  // a part of what()
};

// Loads `text` and checks the CaseError it must raise.
void expect_error(const std::string& text, const Expected& expected, const std::vector<CaseOverride>& overrides = {}) {
  try {
    load_case_text(text, overrides, "test.yaml");
    ADD_FAILURE() << "no CaseError; expected one for key '" << expected.key << "'";
  } catch (const CaseError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.key(), expected.key) << what;
    EXPECT_EQ(e.line(), expected.line) << what;
    EXPECT_NE(what.find("key '" + expected.key + "'"), std::string::npos) << what;
    EXPECT_NE(what.find(expected.message), std::string::npos) << what;
    const std::string place = expected.line > 0 ? "test.yaml:" + std::to_string(expected.line) + ":" : "test.yaml";
    EXPECT_EQ(what.rfind(place, 0), 0u) << what;
  }
}

// --- Good cases -------------------------------------------------------------------------------

TEST(CaseLoader, BaseCaseLoads) {
  const pb::ScenarioSpec spec = load_case_text(base());
  EXPECT_EQ(spec.dimensions(), 2);
  EXPECT_DOUBLE_EQ(spec.dp(), 0.02);
  ASSERT_EQ(spec.bodies_size(), 2);
  EXPECT_EQ(spec.bodies(0).kind(), pb::BOUNDARY);
  ASSERT_EQ(spec.bodies(0).subtract_size(), 1);
  EXPECT_DOUBLE_EQ(spec.bodies(0).subtract(0).box().max(1), 0.9);
  EXPECT_EQ(spec.bodies(1).kind(), pb::FLUID);
  EXPECT_TRUE(spec.bodies(1).initial().hydrostatic());
  EXPECT_EQ(spec.probes(1).kind(), pb::FRONT);
  EXPECT_EQ(spec.probes(1).axis(), "x");
}

TEST(CaseLoader, DefaultsAreApplied) {
  const pb::ScenarioSpec spec = load_case_text(without_lines(3, 3));  // no h_over_dp
  EXPECT_DOUBLE_EQ(spec.h_over_dp(), 1.3);
  EXPECT_DOUBLE_EQ(spec.numerics().cfl(), 0.2);
  EXPECT_DOUBLE_EQ(spec.numerics().min_dt(), 1e-12);
  EXPECT_DOUBLE_EQ(spec.output().interval(), 1.0 / 100);
  EXPECT_TRUE(spec.output().has_hdf5() && spec.output().hdf5());
  EXPECT_DOUBLE_EQ(spec.materials(0).water().density(), 1000);
  EXPECT_DOUBLE_EQ(spec.materials(0).water().sound_speed(), 0);  // Eq. 24a needs the geometry: the solver's job
  EXPECT_DOUBLE_EQ(spec.materials(0).water().delta(), 0.1);
  EXPECT_DOUBLE_EQ(spec.materials(0).water().viscosity_alpha(), 0.01);
  EXPECT_EQ(spec.probes(0).phase(), "water");
}

TEST(CaseLoader, GivenValuesAreKeptOverDefaults) {
  const pb::ScenarioSpec spec =
      load_case_text(base() + "numerics: {cfl: 0.3}\noutput: {interval: 0.05, hdf5: false, vtk: true}\n");
  EXPECT_DOUBLE_EQ(spec.numerics().cfl(), 0.3);
  EXPECT_DOUBLE_EQ(spec.output().interval(), 0.05);
  EXPECT_FALSE(spec.output().hdf5());
  EXPECT_TRUE(spec.output().vtk());
}

TEST(CaseLoader, PolygonVerticesArePairs) {
  const pb::ScenarioSpec spec =
      load_case_text(with_line(21, "    shape: {polygon: {vertices: [[0, 0], [1, 0], [0, 0.5]]}}"));
  const pb::Polygon& polygon = spec.bodies(1).shape().polygon();
  ASSERT_EQ(polygon.vertices_size(), 3);
  EXPECT_DOUBLE_EQ(polygon.vertices(1).x(), 1);
  EXPECT_DOUBLE_EQ(polygon.vertices(2).z(), 0.5);
}

TEST(CaseFiles, HydrostaticTank2d) {
  const pb::ScenarioSpec spec = load_case_file(kCases + "hydrostatic_tank_2d.yaml");
  EXPECT_EQ(spec.name(), "hydrostatic_tank_2d");
  EXPECT_EQ(spec.dimensions(), 2);
  EXPECT_DOUBLE_EQ(spec.dp(), 0.02);
  EXPECT_DOUBLE_EQ(spec.end_time(), 2.0);
  EXPECT_DOUBLE_EQ(spec.output().interval(), 0.02);  // the default end_time / 100
  ASSERT_EQ(spec.bodies_size(), 2);
  const pb::Box& water = spec.bodies(1).shape().box();
  EXPECT_DOUBLE_EQ(water.max(0) - water.min(0), 1.0);
  EXPECT_DOUBLE_EQ(water.max(1) - water.min(1), 0.5);
  ASSERT_EQ(spec.probes_size(), 2);
  EXPECT_EQ(spec.probes(0).kind(), pb::POINT);
  EXPECT_EQ(spec.probes(1).kind(), pb::MEAN);
}

TEST(CaseFiles, HydrostaticTank3d) {
  const pb::ScenarioSpec spec = load_case_file(kCases + "hydrostatic_tank_3d.yaml");
  EXPECT_EQ(spec.dimensions(), 3);
  EXPECT_DOUBLE_EQ(spec.end_time(), 1.0);
  ASSERT_EQ(spec.gravity_size(), 3);
  EXPECT_DOUBLE_EQ(spec.gravity(2), -9.81);
  const pb::Box& water = spec.bodies(1).shape().box();
  EXPECT_DOUBLE_EQ(water.max(2), 0.3);
  EXPECT_EQ(spec.probes(0).position_size(), 3);
}

TEST(CaseFiles, DamBreak2d) {
  const pb::ScenarioSpec spec = load_case_file(kCases + "dam_break_2d.yaml");
  EXPECT_DOUBLE_EQ(spec.dp(), 0.00365);
  EXPECT_DOUBLE_EQ(spec.end_time(), 0.4);
  EXPECT_DOUBLE_EQ(spec.output().interval(), 0.02);
  const pb::Box& column = spec.bodies(1).shape().box();
  EXPECT_DOUBLE_EQ(column.max(0), 0.146);
  EXPECT_DOUBLE_EQ(column.max(1), 0.292);
  EXPECT_DOUBLE_EQ(spec.bodies(0).subtract(0).box().max(0), 0.584);
  EXPECT_EQ(spec.probes(0).kind(), pb::FRONT);
  EXPECT_EQ(spec.probes(0).phase(), "water");
}

TEST(CaseFiles, DamBreak3d) {
  const pb::ScenarioSpec spec = load_case_file(kCases + "dam_break_3d.yaml");
  EXPECT_DOUBLE_EQ(spec.dp(), 0.0103);
  EXPECT_DOUBLE_EQ(spec.h_over_dp(), 1.732);
  EXPECT_DOUBLE_EQ(spec.numerics().cfl(), 0.2);
  EXPECT_DOUBLE_EQ(spec.output().interval(), 0.05);
  ASSERT_EQ(spec.bodies_size(), 3);
  EXPECT_EQ(spec.bodies(1).name(), "obstacle");
  EXPECT_EQ(spec.bodies(1).kind(), pb::BOUNDARY);
  EXPECT_DOUBLE_EQ(spec.bodies(1).shape().box().max(2), 0.45);
  EXPECT_EQ(spec.probes(1).kind(), pb::ELEVATION);
  EXPECT_EQ(spec.probes(1).position_size(), 2);
}

// --- Overrides ----------------------------------------------------------------------------------

TEST(CaseOverrides, ParseKeyAndValue) {
  const CaseOverride o = parse_override("bodies[0].shape.box.max=[0.1, 0.2]");
  EXPECT_EQ(o.key, "bodies[0].shape.box.max");
  EXPECT_EQ(o.value, "[0.1, 0.2]");
}

TEST(CaseOverrides, BadSyntaxIsAnError) {
  for (const char* text : {"dp", "=0.1", "dp=", "a..b=1", "bodies[x].name=a", "bodies[0.name=a", "Dp=1", "dp=[1, 2"}) {
    try {
      parse_override(text);
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const CaseError& e) {
      EXPECT_EQ(e.key(), "--set") << text;
    }
  }
}

TEST(CaseOverrides, ChangeScalarsListsAndMissingSections) {
  const pb::ScenarioSpec spec = load_case_file(
      kCases + "dam_break_2d.yaml",
      {parse_override("dp=0.005"), parse_override("bodies[1].shape.box.max=[0.1,0.2]"),
       parse_override("materials[0].water.sound_speed=30"), parse_override("domain.periodic=[true, false]")});
  EXPECT_DOUBLE_EQ(spec.dp(), 0.005);
  EXPECT_DOUBLE_EQ(spec.bodies(1).shape().box().max(0), 0.1);
  EXPECT_DOUBLE_EQ(spec.bodies(1).shape().box().max(1), 0.2);
  EXPECT_DOUBLE_EQ(spec.materials(0).water().sound_speed(), 30);
  ASSERT_EQ(spec.domain().periodic_size(), 2);
  EXPECT_TRUE(spec.domain().periodic(0));

  // A section the file does not have is created.
  const pb::ScenarioSpec hydro =
      load_case_file(kCases + "hydrostatic_tank_2d.yaml", {parse_override("numerics.cfl=0.1")});
  EXPECT_DOUBLE_EQ(hydro.numerics().cfl(), 0.1);
}

TEST(CaseOverrides, UnknownKeyIsAnError) {
  expect_error(base(), {"bodies[0].shap.box.max", -1, "unknown key 'shap' in bodies[0]"},
               {parse_override("bodies[0].shap.box.max=[1, 1]")});
  expect_error(base(), {"timestep", -1, "from --set timestep=0.1"}, {parse_override("timestep=0.1")});
}

TEST(CaseOverrides, IndexOutOfRangeIsAnError) {
  expect_error(base(), {"bodies[5].name", -1, "has 2 elements"}, {parse_override("bodies[5].name=x")});
}

TEST(CaseOverrides, BadValueNamesTheOverride) {
  expect_error(base(),
               {"dp", -1,
                "expected a number, got 'abc' (or a number and a unit of a length: m, cm, mm, km) "
                "(from --set dp=abc)"},
               {parse_override("dp=abc")});
  expect_error(base(), {"dp", -1, "must be greater than 0 (is -1) (from --set dp=-1)"}, {parse_override("dp=-1")});
}

TEST(CaseOverrides, PolygonIn3dCase) {
  try {
    load_case_file(kCases + "dam_break_3d.yaml",
                   {parse_override("bodies[2].shape={polygon: {vertices: [[0, 0], [0.4, 0], [0, 0.3]]}}")});
    ADD_FAILURE() << "a polygon in a 3D case was accepted";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), "bodies[2].shape.polygon");
    EXPECT_EQ(e.line(), -1);
    EXPECT_NE(std::string(e.what()).find("extruded_polygon"), std::string::npos) << e.what();
  }
}

// --- Errors: the YAML itself --------------------------------------------------------------------

TEST(CaseErrors, MalformedYamlGivesYamlCppsLine) {
  expect_error(with_line(15, "    shape: {box: {min: [-0.1, -0.1], max: [1.1, 0.6]}"),
               {"(yaml)", 16, "end of map flow not found"});
  expect_error(with_line(4, "end_time: 1.0\n  bad: indentation"), {"(yaml)", 5, ""});
}

TEST(CaseErrors, DuplicatedKey) { expect_error(with_line(3, "dp: 0.03"), {"dp", 3, "given twice (first at line 2)"}); }

TEST(CaseErrors, DuplicatedNestedKey) {
  expect_error(with_line(7, "  max: [1.2, 1.0]\n  max: [1.2, 1.1]"), {"domain.max", 8, "given twice"});
}

TEST(CaseErrors, EmptyOrNonMappingCase) {
  expect_error("", {"(root)", -1, "empty"});
  expect_error("- 1\n- 2\n", {"(root)", 1, "a mapping"});
}

// --- Errors: keys and types ---------------------------------------------------------------------

TEST(CaseErrors, MissingDp) { expect_error(without_lines(2, 2), {"dp", -1, "is missing"}); }

TEST(CaseErrors, MissingDimensions) { expect_error(without_lines(1, 1), {"dimensions", -1, "is missing"}); }

TEST(CaseErrors, DpNotANumber) {
  expect_error(with_line(2, "dp: abc"), {"dp", 2, "expected a number, got 'abc'"});
  expect_error(with_line(2, "dp: \"0.02\""), {"dp", 2, "expected a number"});
  expect_error(with_line(2, "dp: [0.02]"), {"dp", 2, "expected a number, got a list"});
  expect_error(with_line(2, "dp:"), {"dp", 2, "has no value"});
}

TEST(CaseErrors, UnknownTopLevelKey) {
  expect_error(with_line(5, "time_step: 0.001\ndomain:"),
               {"time_step", 5, "unknown key (known here: name, description"});
}

TEST(CaseErrors, UnknownNestedKey) {
  expect_error(with_line(21, "    shap: {box: {min: [0, 0], max: [1, 0.5]}}"), {"bodies[1].shap", 21, "unknown key"});
  expect_error(with_line(11, "    water: {density: 1000, viscosity: 0.1}"),
               {"materials[0].water.viscosity", 11, "unknown key"});
}

TEST(CaseErrors, ScalarWhereListExpected) {
  expect_error(with_line(8, "gravity: 9.81"), {"gravity", 8, "expected a list, got '9.81'"});
}

TEST(CaseErrors, TextInsideNumberList) {
  expect_error(with_line(8, "gravity: [0, down]"), {"gravity[1]", 8, "expected a number, got 'down'"});
}

TEST(CaseErrors, ScalarWhereMappingExpected) {
  expect_error(with_line(5, "domain: 1\nnot_domain:"), {"domain", 5, "expected a mapping"});
}

TEST(CaseErrors, DimensionsNotAWholeNumber) {
  expect_error(with_line(1, "dimensions: 2.5"), {"dimensions", 1, "expected a whole number"});
}

TEST(CaseErrors, UnknownEnumValue) {
  expect_error(with_line(19, "    kind: liquid"), {"bodies[1].kind", 19, "expected one of fluid, boundary"});
}

TEST(CaseErrors, ShapeWithTwoKinds) {
  expect_error(
      with_line(21, "    shape: {box: {min: [0, 0], max: [1, 0.5]}, polygon: {vertices: [[0, 0], [1, 0], [0, 1]]}}"),
      {"bodies[1].shape.polygon", 21, "cannot be given together with 'box'"});
}

TEST(CaseErrors, VertexNotAPair) {
  expect_error(with_line(21, "    shape: {polygon: {vertices: [[0, 0], [1, 0, 2], [0, 0.5]]}}"),
               {"bodies[1].shape.polygon.vertices[1]", 21, "[x, z] pair"});
}

// --- Errors: values -----------------------------------------------------------------------------

TEST(CaseErrors, DimensionsNot2Or3) {
  expect_error(with_line(1, "dimensions: 4"), {"dimensions", 1, "must be 2 or 3"});
}

TEST(CaseErrors, DpNotPositive) {
  expect_error(with_line(2, "dp: 0"), {"dp", 2, "must be greater than 0"});
  expect_error(with_line(2, "dp: -0.01"), {"dp", 2, "must be greater than 0"});
}

TEST(CaseErrors, EndTimeNotPositive) {
  expect_error(with_line(4, "end_time: 0"), {"end_time", 4, "must be greater than 0"});
}

TEST(CaseErrors, HOverDpOutOfRange) {
  expect_error(with_line(3, "h_over_dp: 0.5"), {"h_over_dp", 3, "must be in [1, 3]"});
  expect_error(with_line(3, "h_over_dp: 3.5"), {"h_over_dp", 3, "must be in [1, 3]"});
}

TEST(CaseErrors, DomainMinNotBelowMax) {
  expect_error(with_line(7, "  max: [1.2, -0.2]"), {"domain.max", 7, "on axis z"});
}

TEST(CaseErrors, DomainMissing) { expect_error(without_lines(5, 7), {"domain", -1, "is missing"}); }

TEST(CaseErrors, DomainWrongLength) {
  expect_error(with_line(6, "  min: [-0.2, -0.2, -0.2]"), {"domain.min", 6, "has 3 components"});
}

TEST(CaseErrors, GravityWrongLength) {
  expect_error(with_line(8, "gravity: [0, 0, -9.81]"), {"gravity", 8, "has 3 components"});
}

TEST(CaseErrors, UndefinedMaterial) {
  expect_error(with_line(20, "    material: sand"),
               {"bodies[1].material", 20, "'sand' is not a material (defined: water)"});
}

TEST(CaseErrors, MaterialWithoutModel) {
  expect_error(with_line(11, "    description: none\n"), {"materials[0].description", 11, "unknown key"});
  expect_error(without_lines(11, 11), {"materials[0]", 10, "has no model"});
}

TEST(CaseErrors, NegativeWaterParameter) {
  expect_error(with_line(11, "    water: {density: 1000, sound_speed: -5}"),
               {"materials[0].water.sound_speed", 11, "must not be negative"});
}

TEST(CaseErrors, DuplicateNames) {
  expect_error(with_line(11, "    water: {density: 1000}\n  - name: water\n    water: {}"),
               {"materials[1].name", 12, "already the name of materials[0]"});
  expect_error(with_line(18, "  - name: tank"), {"bodies[1].name", 18, "already the name of bodies[0]"});
  expect_error(with_line(25, "  - {name: p, kind: front, axis: x}"),
               {"probes[1].name", 25, "already the name of probes[0]"});
}

TEST(CaseErrors, FluidBodyWithoutMaterial) {
  expect_error(without_lines(20, 20), {"bodies[1].material", 18, "a fluid body is made of a material"});
}

TEST(CaseErrors, BodyWithoutKind) { expect_error(without_lines(19, 19), {"bodies[1].kind", 18, "is missing"}); }

TEST(CaseErrors, NoBodies) {
  std::vector<std::string> lines = kBase;
  lines.erase(lines.begin() + 12, lines.begin() + 22);
  lines[11] = "bodies: []";
  expect_error(join(lines), {"bodies", 12, "a case needs at least one body"});
}

TEST(CaseErrors, NoFluidBody) { expect_error(without_lines(18, 22), {"bodies", 12, "has no fluid body"}); }

TEST(CaseErrors, BoxMinNotBelowMax) {
  expect_error(with_line(21, "    shape: {box: {min: [0, 0], max: [1, 0]}}"),
               {"bodies[1].shape.box.max", 21, "on axis z"});
}

TEST(CaseErrors, BoxWrongLength) {
  expect_error(with_line(17, "      - box: {min: [0, 0, 0], max: [1, 0.9]}"),
               {"bodies[0].subtract[0].box.min", 17, "has 3 components"});
}

TEST(CaseErrors, BodyOutsideDomain) {
  expect_error(with_line(21, "    shape: {box: {min: [0, 0], max: [1, 1.5]}}"),
               {"bodies[1].shape.box.max", 21, "outside the domain"});
}

TEST(CaseErrors, ShapeMissing) { expect_error(without_lines(21, 21), {"bodies[1].shape", 18, "names no shape"}); }

TEST(CaseErrors, PolygonWithTooFewVertices) {
  expect_error(with_line(21, "    shape: {polygon: {vertices: [[0, 0], [1, 0]]}}"),
               {"bodies[1].shape.polygon.vertices", 21, "a polygon needs at least 3"});
}

TEST(CaseErrors, ExtrudedPolygonIn2dCase) {
  expect_error(with_line(21, "    shape: {extruded_polygon: {vertices: [[0, 0], [1, 0], [0, 1]], y_min: 0, y_max: 1}}"),
               {"bodies[1].shape.extruded_polygon", 21, "is a 3D shape"});
}

TEST(CaseErrors, ProbeOfUnknownKind) {
  expect_error(with_line(24, "  - {name: p, kind: pointy, field: pressure, position: [0.5, 0.1]}"),
               {"probes[0].kind", 24, "expected one of point, elevation, front, max, mean, got 'pointy'"});
}

TEST(CaseErrors, ProbeFieldUnknown) {
  expect_error(with_line(24, "  - {name: p, kind: point, field: temperature, position: [0.5, 0.1]}"),
               {"probes[0].field", 24, "'temperature' is not a field"});
  expect_error(with_line(24, "  - {name: p, kind: max, field: velocity_y}"), {"probes[0].field", 24, "not a field"});
}

TEST(CaseErrors, ProbePhaseUnknown) {
  expect_error(with_line(24, "  - {name: p, kind: mean, field: pressure, phase: air}"),
               {"probes[0].phase", 24, "'air' is not a phase"});
}

TEST(CaseErrors, ProbeOutsideDomain) {
  expect_error(with_line(24, "  - {name: p, kind: point, field: pressure, position: [5, 0.1]}"),
               {"probes[0].position", 24, "outside the domain on axis x"});
}

TEST(CaseErrors, FrontProbeAxis) {
  expect_error(with_line(25, "  - {name: front, kind: front, axis: y}"),
               {"probes[1].axis", 25, "not an axis of this case"});
  expect_error(with_line(25, "  - {name: front, kind: front}"), {"probes[1].axis", 25, "is missing"});
}

TEST(CaseErrors, NegativeOutputInterval) {
  expect_error(base() + "output:\n  interval: -0.1\n", {"output.interval", 27, "must not be negative"});
}

TEST(CaseErrors, CflOutOfRange) {
  expect_error(base() + "numerics: {cfl: 1.5}\n", {"numerics.cfl", 26, "must be in (0, 1]"});
  expect_error(base() + "numerics: {cfl: -0.1}\n", {"numerics.cfl", 26, "must be in (0, 1]"});
}

// --- Files and specs from elsewhere -------------------------------------------------------------

TEST(CaseErrors, FileErrorsNameTheFileAndLine) {
  const std::string path = kBadCases + "unknown_nested_key.yaml";
  try {
    load_case_file(path);
    ADD_FAILURE() << "no error";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), "bodies[0].shape.box.mx");
    EXPECT_EQ(e.line(), 14);
    EXPECT_EQ(std::string(e.what()).rfind(path + ":14:", 0), 0u) << e.what();
  }
  try {
    load_case_file(kBadCases + "syntax_error.yaml");
    ADD_FAILURE() << "no error";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), "(yaml)");
    EXPECT_EQ(e.line(), 8);
  }
  EXPECT_THROW(load_case_file(kBadCases + "no_such_file.yaml"), CaseError);
}

TEST(ValidateSpec, SpecFromTheApiHasNoLine) {
  pb::ScenarioSpec spec = load_case_text(base());
  EXPECT_NO_THROW(validate_spec(spec));
  spec.mutable_bodies(1)->mutable_shape()->mutable_box()->set_max(0, -1);
  try {
    validate_spec(spec);
    ADD_FAILURE() << "no error";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), "bodies[1].shape.box.max");
    EXPECT_EQ(e.line(), -1);
    EXPECT_EQ(std::string(e.what()).rfind("key 'bodies[1].shape.box.max': must be greater than", 0), 0u) << e.what();
  }
}

TEST(ValidateSpec, ZeroMeansDefault) {
  pb::ScenarioSpec spec = load_case_text(base());
  spec.set_h_over_dp(0);
  spec.mutable_numerics()->set_cfl(0);
  spec.mutable_output()->set_interval(0);
  EXPECT_NO_THROW(validate_spec(spec));
  apply_defaults(spec);
  EXPECT_DOUBLE_EQ(spec.h_over_dp(), 1.3);
  EXPECT_DOUBLE_EQ(spec.output().interval(), 0.01);
}

// --- Soil materials, soil bodies, hydraulics -----------------------------------------------------

// A small soil case (Table 2's soil on an impermeable base, periodic in x); the soil tests break it
// one line at a time.
const std::vector<std::string> kSoilBase = {
    "dimensions: 2",                                                                          // 1
    "dp: 0.02",                                                                               // 2
    "h_over_dp: 1.8",                                                                         // 3
    "end_time: 100.0",                                                                        // 4
    "domain:",                                                                                // 5
    "  min: [0.0, -0.08]",                                                                    // 6
    "  max: [0.24, 1.1]",                                                                     // 7
    "  periodic: [true, false]",                                                              // 8
    "gravity: [0, -9.81]",                                                                    // 9
    "materials:",                                                                             // 10
    "  - name: sand",                                                                         // 11
    "    soil:",                                                                              // 12
    "      grain_density: 2650",                                                              // 13
    "      porosity: 0.3",                                                                    // 14
    "      saturated_conductivity: 1e-3",                                                     // 15
    "      water_bulk_modulus: 2e6",                                                          // 16
    "      hydraulic: {van_genuchten: {s_min: 0.3, s_max: 1.0, lambda: 0.447, p_ref: 19357}}",  // 17
    "      mechanical: {drucker_prager: {youngs_modulus: 50e6, poisson_ratio: 0.3, cohesion: 10e3, "
    "residual_cohesion: 3e3, friction_angle: 34, residual_friction_angle: 32, softening_coefficient: 1, "
    "suction_cohesion: 10e3, suction_cohesion_rate: 10, suction_friction_rate: 2}}",        // 18
    "bodies:",                                                                                // 19
    "  - name: base",                                                                         // 20
    "    kind: boundary",                                                                     // 21
    "    shape: {box: {min: [0, -0.08], max: [0.24, 0]}}",                                    // 22
    "  - name: slope",                                                                        // 23
    "    kind: fluid",                                                                        // 24
    "    material: sand",                                                                     // 25
    "    shape: {box: {min: [0, 0], max: [0.24, 1.0]}}",                                      // 26
    "    initial: {water_table: 0.5, k0: 0.5}",                                               // 27
    "hydraulics:",                                                                            // 28
    "  rainfall_intensity: 1e-5",                                                             // 29
    "  ponding_pressure: 0",                                                                  // 30
    "probes:",                                                                                // 31
    "  - {name: p, kind: point, field: pore_pressure, phase: soil, position: [0.12, 0.5]}",   // 32
};

std::string soil_base() { return join(kSoilBase); }

std::string soil_with_line(int n, const std::string& text) {
  std::vector<std::string> lines = kSoilBase;
  lines.at(n - 1) = text;
  return join(lines);
}

std::string soil_without_lines(int first, int last) {
  std::vector<std::string> lines = kSoilBase;
  lines.erase(lines.begin() + first - 1, lines.begin() + last);
  return join(lines);
}

// The mechanical line (18) with one Drucker-Prager parameter set to `value`.
std::string drucker_prager_line(const std::string& parameters) {
  return "      mechanical: {drucker_prager: {" + parameters + "}}";
}

constexpr double kDegree = 3.14159265358979323846 / 180.0;

TEST(SoilErrors, CflAboveTheSeepageLimit) {
  // The explicit pore water is stable up to C0 = 0.55 (test_seepage_exchange.cpp); water alone up to 1.
  expect_error(soil_base() + "numerics: {cfl: 0.6}\n", {"numerics.cfl", 33, "must be at most 0.55 with soil"});
  EXPECT_NO_THROW(load_case_text(soil_base() + "numerics: {cfl: 0.55}\n"));
  EXPECT_NO_THROW(load_case_text(base() + "numerics: {cfl: 0.9}\n"));
}

TEST(SoilCases, SoilCaseLoadsWithDefaults) {
  const pb::ScenarioSpec spec = load_case_text(soil_base());
  ASSERT_TRUE(spec.materials(0).has_soil());
  const pb::SoilModel& soil = spec.materials(0).soil();
  EXPECT_DOUBLE_EQ(soil.grain_density(), 2650);
  EXPECT_DOUBLE_EQ(soil.porosity(), 0.3);
  EXPECT_DOUBLE_EQ(soil.pore_sound_speed(), 10 * 1e-3);  // c_pw0 = 10 K_sat
  EXPECT_DOUBLE_EQ(soil.delta(), 0.1);
  EXPECT_DOUBLE_EQ(soil.viscosity_alpha(), 0.1);
  EXPECT_FALSE(soil.rigid());
  EXPECT_DOUBLE_EQ(soil.hydraulic().van_genuchten().p_ref(), 19357);
  const pb::DruckerPragerModel& dp = soil.mechanical().drucker_prager();
  EXPECT_DOUBLE_EQ(dp.friction_angle(), 34);  // degrees in the spec
  EXPECT_DOUBLE_EQ(dp.atmospheric_pressure(), 101e3);
  EXPECT_TRUE(spec.bodies(1).initial().has_water_table());
  EXPECT_DOUBLE_EQ(spec.bodies(1).initial().water_table(), 0.5);
  EXPECT_DOUBLE_EQ(spec.bodies(1).initial().k0(), 0.5);
  EXPECT_DOUBLE_EQ(spec.hydraulics().rainfall_intensity(), 1e-5);
  EXPECT_FALSE(spec.hydraulics().has_drying_pressure());
  EXPECT_EQ(spec.probes(0).phase(), "soil");

  // Left out: K_w 2e6, s_max 1, the residual strength = the peak one.
  const pb::ScenarioSpec defaults = load_case_text(soil_with_line(16, "      delta: 0.2"));  // no K_w
  EXPECT_DOUBLE_EQ(defaults.materials(0).soil().water_bulk_modulus(), 2e6);
  EXPECT_DOUBLE_EQ(defaults.materials(0).soil().delta(), 0.2);
  const pb::ScenarioSpec peak = load_case_text(soil_with_line(
      18, drucker_prager_line("youngs_modulus: 1e7, poisson_ratio: 0.25, cohesion: 5e3, friction_angle: 30")));
  const pb::DruckerPragerModel& d = peak.materials(0).soil().mechanical().drucker_prager();
  EXPECT_DOUBLE_EQ(d.residual_cohesion(), 5e3);
  EXPECT_DOUBLE_EQ(d.residual_friction_angle(), 30);
  const pb::ScenarioSpec gardner =
      load_case_text(soil_with_line(17, "      hydraulic: {gardner: {s_min: 0.23, alpha: 2}}"));
  EXPECT_DOUBLE_EQ(gardner.materials(0).soil().hydraulic().gardner().s_max(), 1);
}

TEST(SoilCases, SoilMaterialForTheEngine) {
  const pb::ScenarioSpec spec = load_case_text(soil_base());
  ASSERT_EQ(soil_material_indices(spec), std::vector<int>{0});
  const SoilMaterial m = soil_material(spec, 0);
  EXPECT_DOUBLE_EQ(m.grain_density, 2650);
  EXPECT_DOUBLE_EQ(m.saturated_conductivity, 1e-3);
  EXPECT_DOUBLE_EQ(m.water_bulk_modulus, 2e6);
  EXPECT_DOUBLE_EQ(m.pore_sound_speed, 1e-2);
  EXPECT_DOUBLE_EQ(m.delta, 0.1);
  EXPECT_DOUBLE_EQ(m.viscosity_alpha, 0.1);
  EXPECT_FALSE(m.rigid);
  ASSERT_EQ(m.hydraulic.kind, HydraulicModel<double>::Kind::van_genuchten);
  EXPECT_DOUBLE_EQ(m.hydraulic.van_genuchten.lambda, 0.447);
  // The model is wired: Eq. 14 (ERRATA.md) with Table 2's constants, saturated at p_c <= 0.
  EXPECT_DOUBLE_EQ(m.hydraulic.saturation(-1.0), 1.0);
  EXPECT_NEAR(m.hydraulic.saturation(7e3), 0.3 + 0.7 * std::pow(1 + std::pow(7e3 / 19357, 1 / (1 - 0.447)), -0.447),
              1e-12);
  const SoilModel<double>& dp = m.mechanical;
  ASSERT_EQ(dp.kind, SoilModel<double>::Kind::drucker_prager);
  EXPECT_DOUBLE_EQ(dp.youngs_modulus, 50e6);
  EXPECT_DOUBLE_EQ(dp.poisson_ratio, 0.3);
  EXPECT_DOUBLE_EQ(dp.peak_cohesion, 10e3);
  EXPECT_DOUBLE_EQ(dp.residual_cohesion, 3e3);
  EXPECT_NEAR(dp.peak_friction_angle, 34 * kDegree, 1e-15);  // degrees → radians
  EXPECT_NEAR(dp.residual_friction_angle, 32 * kDegree, 1e-15);
  EXPECT_DOUBLE_EQ(dp.dilatancy_angle, 0);
  EXPECT_DOUBLE_EQ(dp.softening_coefficient, 1);
  EXPECT_DOUBLE_EQ(dp.suction_cohesion, 10e3);
  EXPECT_DOUBLE_EQ(dp.suction_cohesion_rate, 10);
  EXPECT_NEAR(dp.suction_friction_rate, 2 * kDegree, 1e-15);
  EXPECT_DOUBLE_EQ(dp.atmospheric_pressure, 101e3);

  // Gardner and Liakopoulos read the head p_c/(ρ_w0 |g|); a soil-only case has ρ_w0 = 1000.
  const pb::ScenarioSpec g = load_case_text(soil_with_line(17, "      hydraulic: {gardner: {s_min: 0.23, alpha: 2}}"));
  EXPECT_DOUBLE_EQ(reference_water_density(g), 1000);
  const SoilMaterial gm = soil_material(g, 0);
  ASSERT_EQ(gm.hydraulic.kind, HydraulicModel<double>::Kind::gardner);
  EXPECT_NEAR(gm.hydraulic.gardner.unit_weight, 9810, 1e-9);
  EXPECT_DOUBLE_EQ(gm.hydraulic.gardner.s_max, 1);
  const pb::ScenarioSpec l = load_case_text(soil_with_line(17, "      hydraulic: {liakopoulos: {}}"));
  ASSERT_EQ(soil_material(l, 0).hydraulic.kind, HydraulicModel<double>::Kind::liakopoulos);

  // A rigid soil needs no mechanical model: a placeholder that validates; K0 is then 1.
  const pb::ScenarioSpec rigid = load_case_text(soil_with_line(18, "      rigid: true"));
  const SoilMaterial rm = soil_material(rigid, 0);
  EXPECT_TRUE(rm.rigid);
  EXPECT_EQ(rm.mechanical.validate(), "");
  pb::InitialState no_k0;
  EXPECT_DOUBLE_EQ(earth_pressure_coefficient(rm, no_k0), 1.0);
  EXPECT_NEAR(earth_pressure_coefficient(m, no_k0), 0.3 / 0.7, 1e-15);  // ν/(1 − ν)
  EXPECT_DOUBLE_EQ(earth_pressure_coefficient(m, spec.bodies(1).initial()), 0.5);
}

TEST(SoilCases, SoilOnlyAndSoilWithWaterCases) {
  // ρ_w0 is the water material's when there is one.
  const pb::ScenarioSpec spec = load_case_text(soil_with_line(
      11, "  - name: water\n    water: {density: 1020}\n  - name: sand"));
  EXPECT_DOUBLE_EQ(reference_water_density(spec), 1020);
  EXPECT_EQ(soil_material_indices(spec), std::vector<int>{1});
  expect_error(soil_with_line(11, "  - name: water\n    water: {}\n  - name: sea\n    water: {}\n  - name: sand"),
               {"materials[1]", 13, "a case has one water material; 'water' is already one"});
  // A case needs a water or a soil material.
  std::vector<std::string> lines = kSoilBase;
  lines.erase(lines.begin() + 10, lines.begin() + 18);
  lines[9] = "materials: []";
  expect_error(join(lines), {"materials", 10, "a case needs a water or a soil material"});
}

TEST(SoilCases, HydraulicForcingTimeSeriesIsPiecewiseConstant) {
  const pb::ScenarioSpec constant = load_case_text(soil_base());
  HydraulicForcing f = hydraulic_forcing(constant, 50.0);
  EXPECT_DOUBLE_EQ(f.rainfall_intensity, 1e-5);
  EXPECT_DOUBLE_EQ(f.ponding_pressure, 0);
  EXPECT_EQ(f.drying_pressure, -std::numeric_limits<double>::infinity());
  EXPECT_FALSE(f.has_region);

  const pb::ScenarioSpec series = load_case_text(soil_with_line(
      29, "  rainfall: [{time: 10, intensity: 2e-5}, {time: 20, intensity: -1e-6}]\n  drying_pressure: -5e4\n"
          "  region: {min: [0.0, 0.5], max: [0.12, 1.0]}"));
  EXPECT_DOUBLE_EQ(hydraulic_forcing(series, 0).rainfall_intensity, 0);  // before the first point
  EXPECT_DOUBLE_EQ(hydraulic_forcing(series, 10).rainfall_intensity, 2e-5);
  EXPECT_DOUBLE_EQ(hydraulic_forcing(series, 19.999).rainfall_intensity, 2e-5);
  EXPECT_DOUBLE_EQ(hydraulic_forcing(series, 20).rainfall_intensity, -1e-6);
  f = hydraulic_forcing(series, 1e6);
  EXPECT_DOUBLE_EQ(f.rainfall_intensity, -1e-6);
  EXPECT_DOUBLE_EQ(f.drying_pressure, -5e4);
  EXPECT_TRUE(f.has_region);
  EXPECT_DOUBLE_EQ(f.region_min[0], 0.0);
  EXPECT_DOUBLE_EQ(f.region_min[1], 0.5);  // (x, z) in 2D
  EXPECT_DOUBLE_EQ(f.region_max[0], 0.12);
  EXPECT_DOUBLE_EQ(f.region_max[1], 1.0);
}

TEST(SoilCases, ShippedSoilCasesLoad) {
  for (const char* name : {"infiltration_1d", "evaporation_1d"}) {
    SCOPED_TRACE(name);
    const pb::ScenarioSpec spec = load_case_file(kCases + name + ".yaml");
    EXPECT_EQ(spec.dimensions(), 2);
    EXPECT_DOUBLE_EQ(spec.dp(), 0.02);
    EXPECT_DOUBLE_EQ(spec.h_over_dp(), 1.8);
    // Rain to half a day, before the base saturates (cases/infiltration_1d.yaml says why).
    EXPECT_DOUBLE_EQ(spec.end_time(), std::string(name) == "infiltration_1d" ? 43200 : 86400);
    EXPECT_DOUBLE_EQ(spec.output().interval(), 8640);
    // The periodic width spans 3 kernel supports with the skin, 6.3 h, in whole spacings.
    const double width = spec.domain().max(0) - spec.domain().min(0);
    EXPECT_GE(width, 6.3 * 1.8 * 0.02);
    EXPECT_LT(width - 0.02, 6.3 * 1.8 * 0.02);
    ASSERT_TRUE(spec.domain().periodic(0));
    const pb::SoilModel& soil = spec.materials(0).soil();
    EXPECT_TRUE(soil.rigid());
    EXPECT_DOUBLE_EQ(soil.porosity(), 0.4);
    EXPECT_NEAR(soil.saturated_conductivity() * 86400, 1.0, 1e-4);  // 1 m/day
    EXPECT_DOUBLE_EQ(soil.water_bulk_modulus(), 2e6);
    EXPECT_DOUBLE_EQ(soil.hydraulic().gardner().s_min(), 0.23);
    EXPECT_DOUBLE_EQ(soil.hydraulic().gardner().alpha(), 2);
    EXPECT_DOUBLE_EQ(spec.bodies(1).initial().water_table(), 0);
    ASSERT_EQ(spec.probes_size(), 6);
    EXPECT_EQ(spec.probes(5).name(), "p_z2_95");
    EXPECT_DOUBLE_EQ(spec.probes(5).position(1), 2.95);
    EXPECT_EQ(spec.probes(5).field(), "pore_pressure");
  }
  EXPECT_NEAR(load_case_file(kCases + "infiltration_1d.yaml").hydraulics().rainfall_intensity() * 86400, 0.1, 1e-5);
  const pb::ScenarioSpec evaporation = load_case_file(kCases + "evaporation_1d.yaml");
  EXPECT_NEAR(evaporation.hydraulics().rainfall_intensity() * 86400, -0.002, 1e-7);
  EXPECT_DOUBLE_EQ(evaporation.hydraulics().drying_pressure(), -1e5);
}

TEST(SoilErrors, ConductivityNotPositive) {
  expect_error(soil_with_line(15, "      saturated_conductivity: 0"),
               {"materials[0].soil.saturated_conductivity", 15, "must be greater than 0 (is 0)"});
  expect_error(soil_with_line(15, "      saturated_conductivity: -1e-4"),
               {"materials[0].soil.saturated_conductivity", 15, "must be greater than 0"});
}

TEST(SoilErrors, PorosityOutsideZeroOne) {
  for (const char* value : {"0", "1", "-0.1", "1.5"})
    expect_error(soil_with_line(14, std::string("      porosity: ") + value),
                 {"materials[0].soil.porosity", 14, "must be in (0, 1)"});
}

TEST(SoilErrors, OtherSoilParameters) {
  expect_error(soil_with_line(13, "      grain_density: 0"), {"materials[0].soil.grain_density", 13, "greater than 0"});
  expect_error(soil_with_line(16, "      water_bulk_modulus: -2e6"),
               {"materials[0].soil.water_bulk_modulus", 16, "must not be negative"});
  expect_error(soil_with_line(16, "      delta: 2"), {"materials[0].soil.delta", 16, "must be in [0, 1]"});
  expect_error(soil_with_line(16, "      viscosity_alpha: -0.1"),
               {"materials[0].soil.viscosity_alpha", 16, "must not be negative"});
  expect_error(soil_with_line(16, "      pore_sound_speed: -1"),
               {"materials[0].soil.pore_sound_speed", 16, "must not be negative"});
}

TEST(SoilErrors, FrictionAngleOutsideZeroToNinety) {
  for (const char* angle : {"90", "95", "-1"})
    expect_error(soil_with_line(18, drucker_prager_line(std::string("youngs_modulus: 1e7, poisson_ratio: 0.3, "
                                                                    "friction_angle: ") + angle)),
                 {"materials[0].soil.mechanical.drucker_prager.friction_angle", 18, "must be in [0, 90) degrees"});
  expect_error(soil_with_line(18, drucker_prager_line("youngs_modulus: 1e7, poisson_ratio: 0.3, friction_angle: 30, "
                                                      "residual_friction_angle: 35")),
               {"materials[0].soil.mechanical.drucker_prager.residual_friction_angle", 18,
                "must not exceed peak_friction_angle"});
  expect_error(soil_with_line(18, drucker_prager_line("youngs_modulus: 1e7, poisson_ratio: 0.3, friction_angle: 30, "
                                                      "dilatancy_angle: 31")),
               {"materials[0].soil.mechanical.drucker_prager.dilatancy_angle", 18, "must not exceed"});
}

TEST(SoilErrors, SoilModelValidateNamesTheKey) {
  // Every message of SoilModel::validate(), under the key of the case file.
  const struct {
    std::string parameters, key, message;
  } cases[] = {
      {"youngs_modulus: 0, poisson_ratio: 0.3", "youngs_modulus", "youngs_modulus must be"},
      {"youngs_modulus: 1e7, poisson_ratio: 0.5", "poisson_ratio", "poisson_ratio must lie in (-1, 0.5)"},
      {"youngs_modulus: 1e7, poisson_ratio: 0.3, cohesion: -1", "cohesion", "peak_cohesion must be"},
      {"youngs_modulus: 1e7, poisson_ratio: 0.3, cohesion: 1e3, residual_cohesion: 2e3", "residual_cohesion",
       "must not exceed peak_cohesion"},
      {"youngs_modulus: 1e7, poisson_ratio: 0.3, softening_coefficient: -1", "softening_coefficient", "must be"},
      {"youngs_modulus: 1e7, poisson_ratio: 0.3, suction_cohesion: -1", "suction_cohesion", "must be"},
      {"youngs_modulus: 1e7, poisson_ratio: 0.3, suction_cohesion_rate: -1", "suction_cohesion_rate", "must be"},
      {"youngs_modulus: 1e7, poisson_ratio: 0.3, suction_friction_rate: -1", "suction_friction_rate", "must be"},
      {"youngs_modulus: 1e7, poisson_ratio: 0.3, atmospheric_pressure: -1", "atmospheric_pressure", "must be"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.parameters);
    expect_error(soil_with_line(18, drucker_prager_line(c.parameters)),
                 {"materials[0].soil.mechanical.drucker_prager." + c.key, 18, c.message});
  }
  expect_error(soil_with_line(18, "      mechanical: {linear_elastic: {youngs_modulus: 1e7, poisson_ratio: 0.6}}"),
               {"materials[0].soil.mechanical.linear_elastic.poisson_ratio", 18, "must lie in (-1, 0.5)"});
  expect_error(soil_with_line(18, "      mechanical: {linear_elastic: {poisson_ratio: 0.2}}"),
               {"materials[0].soil.mechanical.linear_elastic.youngs_modulus", 18, "must be a finite value > 0"});
}

TEST(SoilErrors, SaturationRangeAndHydraulicModelChecks) {
  expect_error(soil_with_line(17, "      hydraulic: {van_genuchten: {s_min: 0.5, s_max: 0.5, lambda: 0.4, "
                                  "p_ref: 1e4}}"),
               {"materials[0].soil.hydraulic.van_genuchten.s_min", 17, "s_min must be less than s_max"});
  expect_error(soil_with_line(17, "      hydraulic: {gardner: {s_min: 0.8, s_max: 0.3, alpha: 2}}"),
               {"materials[0].soil.hydraulic.gardner.s_min", 17, "s_min must be less than s_max"});
  expect_error(soil_with_line(17, "      hydraulic: {gardner: {s_min: 0.2, s_max: 1.2, alpha: 2}}"),
               {"materials[0].soil.hydraulic.gardner.s_max", 17, "s_max must be <= 1"});
  expect_error(soil_with_line(17, "      hydraulic: {gardner: {s_min: -0.1, alpha: 2}}"),
               {"materials[0].soil.hydraulic.gardner.s_min", 17, "s_min must be >= 0"});
  expect_error(soil_with_line(17, "      hydraulic: {van_genuchten: {s_min: 0.1, lambda: 1, p_ref: 1e4}}"),
               {"materials[0].soil.hydraulic.van_genuchten.lambda", 17, "lambda must be in (0, 1)"});
  expect_error(soil_with_line(17, "      hydraulic: {van_genuchten: {s_min: 0.1, lambda: 0.5}}"),
               {"materials[0].soil.hydraulic.van_genuchten.p_ref", 17, "p_ref must be a finite number > 0"});
  expect_error(soil_with_line(17, "      hydraulic: {gardner: {s_min: 0.1, alpha: 0}}"),
               {"materials[0].soil.hydraulic.gardner.alpha", 17, "alpha must be a finite number > 0"});
  // The suction head needs gravity: γ_w = ρ_w0 |g| is the model's unit weight.
  std::vector<std::string> lines = kSoilBase;
  lines[8] = "gravity: [0, 0]";
  lines[16] = "      hydraulic: {gardner: {s_min: 0.1, alpha: 2}}";
  expect_error(join(lines), {"materials[0].soil.hydraulic.gardner", 17, "the case needs gravity"});
  lines[16] = "      hydraulic: {liakopoulos: {}}";
  expect_error(join(lines), {"materials[0].soil.hydraulic.liakopoulos", 17, "unit_weight must be"});
}

TEST(SoilErrors, UnknownOrMissingModels) {
  expect_error(soil_with_line(17, "      hydraulic: {brooks_corey: {lambda: 0.5}}"),
               {"materials[0].soil.hydraulic.brooks_corey", 17, "unknown key (known here: van_genuchten, gardner"});
  expect_error(soil_with_line(18, "      mechanical: {cam_clay: {}}"),
               {"materials[0].soil.mechanical.cam_clay", 18, "unknown key (known here: linear_elastic"});
  expect_error(soil_with_line(17, "      hydraulic: {gardner: {s_min: 0.1, alpha: 2}, liakopoulos: {}}"),
               {"materials[0].soil.hydraulic.liakopoulos", 17, "cannot be given together with 'gardner'"});
  expect_error(soil_without_lines(17, 17), {"materials[0].soil.hydraulic", 12, "has no model"});
  expect_error(soil_with_line(17, "      hydraulic: {}"), {"materials[0].soil.hydraulic", 17, "has no model"});
  expect_error(soil_without_lines(18, 18),
               {"materials[0].soil.mechanical", 12, "only a rigid soil may leave it out"});
}

TEST(SoilErrors, NotANumber) {
  // From a file: YAML's .nan is refused where it is read.
  expect_error(soil_with_line(14, "      porosity: .nan"),
               {"materials[0].soil.porosity", 14, "expected a finite number"});
  expect_error(soil_with_line(27, "    initial: {water_table: .inf}"),
               {"bodies[1].initial.water_table", 27, "expected a finite number"});
  // Over the API: validate_spec finds NaN in every soil field it checks.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const pb::ScenarioSpec good = load_case_text(soil_base());
  const struct {
    std::function<void(pb::ScenarioSpec&)> set;
    std::string key;
  } cases[] = {
      {[&](pb::ScenarioSpec& s) { s.mutable_materials(0)->mutable_soil()->set_porosity(nan); },
       "materials[0].soil.porosity"},
      {[&](pb::ScenarioSpec& s) { s.mutable_materials(0)->mutable_soil()->set_saturated_conductivity(nan); },
       "materials[0].soil.saturated_conductivity"},
      {[&](pb::ScenarioSpec& s) { s.mutable_materials(0)->mutable_soil()->set_grain_density(nan); },
       "materials[0].soil.grain_density"},
      {[&](pb::ScenarioSpec& s) { s.mutable_materials(0)->mutable_soil()->set_water_bulk_modulus(nan); },
       "materials[0].soil.water_bulk_modulus"},
      {[&](pb::ScenarioSpec& s) {
         s.mutable_materials(0)->mutable_soil()->mutable_hydraulic()->mutable_van_genuchten()->set_lambda(nan);
       },
       "materials[0].soil.hydraulic.van_genuchten.lambda"},
      {[&](pb::ScenarioSpec& s) {
         s.mutable_materials(0)->mutable_soil()->mutable_mechanical()->mutable_drucker_prager()->set_friction_angle(
             nan);
       },
       "materials[0].soil.mechanical.drucker_prager.friction_angle"},
      {[&](pb::ScenarioSpec& s) {
         s.mutable_materials(0)->mutable_soil()->mutable_mechanical()->mutable_drucker_prager()->set_cohesion(nan);
       },
       "materials[0].soil.mechanical.drucker_prager.cohesion"},
      {[&](pb::ScenarioSpec& s) { s.mutable_bodies(1)->mutable_initial()->set_water_table(nan); },
       "bodies[1].initial.water_table"},
      {[&](pb::ScenarioSpec& s) { s.mutable_bodies(1)->mutable_initial()->set_k0(nan); }, "bodies[1].initial.k0"},
      {[&](pb::ScenarioSpec& s) { s.mutable_hydraulics()->set_rainfall_intensity(nan); },
       "hydraulics.rainfall_intensity"},
      {[&](pb::ScenarioSpec& s) { s.mutable_hydraulics()->set_ponding_pressure(nan); }, "hydraulics.ponding_pressure"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.key);
    pb::ScenarioSpec spec = good;
    c.set(spec);
    try {
      validate_spec(spec);
      ADD_FAILURE() << "NaN accepted";
    } catch (const CaseError& e) {
      EXPECT_EQ(e.key(), c.key) << e.what();
    }
  }
}

TEST(SoilErrors, SoilBodyIn3dCaseWith2dShape) {
  const std::string text =
      "dimensions: 3\ndp: 0.05\nend_time: 1\n"                                                  // 1-3
      "domain: {min: [0, 0, 0], max: [1, 1, 1]}\n"                                              // 4
      "gravity: [0, 0, -9.81]\n"                                                                // 5
      "materials:\n"                                                                            // 6
      "  - {name: sand, soil: {grain_density: 2650, porosity: 0.3, saturated_conductivity: 1e-3, rigid: true, "
      "hydraulic: {liakopoulos: {}}}}\n"                                                        // 7
      "bodies:\n"                                                                               // 8
      "  - name: slope\n"                                                                       // 9
      "    kind: fluid\n"                                                                       // 10
      "    material: sand\n"                                                                    // 11
      "    shape: {polygon: {vertices: [[0, 0], [1, 0], [0, 0.5]]}}\n";                         // 12
  expect_error(text, {"bodies[0].shape.polygon", 12, "is a 2D shape; a 3D case uses extruded_polygon"});
}

TEST(SoilErrors, InitialState) {
  expect_error(soil_with_line(27, "    initial: {suction: -10}"),
               {"bodies[1].initial.suction", 27, "must be greater than 0"});
  expect_error(soil_with_line(27, "    initial: {suction: 3e6}"),
               {"bodies[1].initial.suction", 27, "must be below the pore water's bulk modulus"});
  expect_error(soil_with_line(27, "    initial: {suction: 1e4, water_table: 0.5}"),
               {"bodies[1].initial.water_table", 27, "cannot be given together with 'suction'"});
  expect_error(soil_with_line(27, "    initial: {water_table: 0.5, k0: -0.5}"),
               {"bodies[1].initial.k0", 27, "must not be negative"});
  expect_error(soil_with_line(27, "    initial: {hydrostatic: true}"),
               {"bodies[1].initial.hydrostatic", 27, "is for water bodies"});
  expect_error(soil_with_line(9, "gravity: [1, 0]"), {"gravity", 9, "must have a downward z component"});
  expect_error(soil_with_line(9, "gravity: [0, 9.81]"), {"gravity", 9, "must have a downward z component"});
  // A rigid soil does not move.
  std::vector<std::string> lines = kSoilBase;
  lines[17] = "      rigid: true";
  lines[26] = "    initial: {velocity: [0, -1]}";
  expect_error(join(lines), {"bodies[1].initial.velocity", 27, "a rigid soil does not move"});
  // The soil state on a water body or a boundary.
  expect_error(with_line(22, "    initial: {water_table: 0.5}"),
               {"bodies[1].initial.water_table", 22, "is for soil bodies"});
  expect_error(with_line(22, "    initial: {k0: 0.5}"), {"bodies[1].initial.k0", 22, "is for soil bodies"});
  expect_error(soil_with_line(22, "    shape: {box: {min: [0, -0.08], max: [0.24, 0]}}\n    initial: {suction: 10}"),
               {"bodies[0].initial", 23, "has no initial state"});
}

TEST(SoilErrors, Hydraulics) {
  expect_error(soil_with_line(29, "  rainfall_intensity: 1e-5\n  rainfall: [{time: 0, intensity: 1e-5}]"),
               {"hydraulics.rainfall", 30, "cannot be given together with rainfall_intensity"});
  expect_error(soil_with_line(29, "  rainfall: [{time: 10, intensity: 1e-5}, {time: 10, intensity: 0}]"),
               {"hydraulics.rainfall[1].time", 29, "must be later than the time of the point before"});
  expect_error(soil_with_line(29, "  rainfall: [{time: -1, intensity: 1e-5}]"),
               {"hydraulics.rainfall[0].time", 29, "must not be negative"});
  expect_error(soil_with_line(29, "  drying_pressure: 0"),
               {"hydraulics.drying_pressure", 29, "must be below ponding_pressure"});
  expect_error(soil_with_line(29, "  drying_pressure: -3e6"),
               {"hydraulics.drying_pressure", 29, "must be above -K_w = -2000000 Pa"});
  expect_error(soil_with_line(29, "  region: {min: [0, 1], max: [0.24, 0.5]}"),
               {"hydraulics.region.max", 29, "must be greater than hydraulics.region.min on axis z"});
  expect_error(soil_with_line(29, "  region: {min: [0], max: [0.24, 0.5]}"),
               {"hydraulics.region.min", 29, "has 1 component"});
  expect_error(base() + "hydraulics: {rainfall_intensity: 1e-5}\n",
               {"hydraulics", 26, "the case has no soil material"});
}

TEST(SoilErrors, DrainedWallsInitialisationAndDamping) {
  // A drained wall is a boundary body with a pore pressure above -K_w, in a case with soil.
  expect_error(soil_with_line(22, "    shape: {box: {min: [0, -0.08], max: [0.24, 0]}}\n    pore_pressure: -3e6"),
               {"bodies[0].pore_pressure", 23, "must be above -K_w = -2000000 Pa"});
  expect_error(soil_with_line(26, "    shape: {box: {min: [0, 0], max: [0.24, 1.0]}}\n    pore_pressure: 0"),
               {"bodies[1].pore_pressure", 27, "give it on a boundary body"});
  expect_error(with_line(15, "    shape: {box: {min: [-0.1, -0.1], max: [1.1, 0.6]}}\n    pore_pressure: 0"),
               {"bodies[0].pore_pressure", 16, "the case has no soil material"});
  // The initialisation stage: a positive duration, known keys, constant conditions.
  expect_error(soil_base() + "initialisation: {duration: 0}\n",
               {"initialisation.duration", 33, "must be greater than 0"});
  expect_error(soil_base() + "initialisation:\n  duration: 20\n  time: 5\n",
               {"initialisation.time", 35, "unknown key (known here: duration, hydraulics)"});
  expect_error(soil_base() + "initialisation:\n  duration: 20\n  hydraulics: {rainfall: [{time: 0, intensity: 0}]}\n",
               {"initialisation.hydraulics.rainfall", 35, "the initialisation stage holds constant conditions"});
  expect_error(soil_base() + "initialisation:\n  duration: 20\n  hydraulics: {surface_pressure: 0, rainfall_intensity: 1e-6}\n",
               {"initialisation.hydraulics.surface_pressure", 35, "cannot be given together with rain"});
  expect_error(soil_base() + "initialisation:\n  duration: 20\n  hydraulics: {surface_pressure: -2e6}\n",
               {"initialisation.hydraulics.surface_pressure", 35, "must be above -K_w = -2000000 Pa"});
  expect_error(base() + "initialisation: {duration: 1, hydraulics: {surface_pressure: 0}}\n",
               {"initialisation.hydraulics", 26, "the case has no soil material"});
  expect_error(soil_with_line(30, "  surface_pressure: 0"),
               {"hydraulics.surface_pressure", 30, "cannot be given together with rain"});
  // The skeleton's damping: not negative, not on a rigid soil.
  expect_error(soil_with_line(16, "      water_bulk_modulus: 2e6\n      damping: -0.1"),
               {"materials[0].soil.damping", 17, "must not be negative"});
  std::vector<std::string> lines = kSoilBase;
  lines[17] = "      rigid: true\n      damping: 0.1";
  expect_error(join(lines), {"materials[0].soil.damping", 19, "a rigid soil does not move"});
  // The compression switch on the artificial viscosity: not on a rigid soil either.
  lines[17] = "      rigid: true\n      viscosity_switch: true";
  expect_error(join(lines), {"materials[0].soil.viscosity_switch", 19, "a rigid soil does not"});
}

TEST(SoilCases, InitialisationStageAndDrainedWallReachTheEngine) {
  const pb::ScenarioSpec spec = load_case_text(
      soil_with_line(22, "    shape: {box: {min: [0, -0.08], max: [0.24, 0]}}\n    pore_pressure: 500") +
      "initialisation: {duration: 20, hydraulics: {surface_pressure: -100}}\n");
  ASSERT_TRUE(spec.has_initialisation());
  EXPECT_DOUBLE_EQ(spec.initialisation().duration(), 20);
  const HydraulicForcing init = initialisation_forcing(spec);
  EXPECT_TRUE(init.has_surface_pressure);
  EXPECT_DOUBLE_EQ(init.surface_pressure, -100);
  EXPECT_DOUBLE_EQ(init.rainfall_intensity, 0);
  const HydraulicForcing main = hydraulic_forcing(spec, 0.0);
  EXPECT_FALSE(main.has_surface_pressure);
  EXPECT_DOUBLE_EQ(main.rainfall_intensity, 1e-5);
  const ParticleSet set = build_particle_set(spec);
  const EngineConfig config = engine_config(spec, set.particles, Precision::double_precision);
  // The engine starts under the stage's conditions; the base is a drained wall at 500 Pa.
  EXPECT_TRUE(config.forcing.has_surface_pressure);
  ASSERT_EQ(config.drained_walls.size(), 1u);
  EXPECT_EQ(config.drained_walls[0].body, 0u);
  EXPECT_DOUBLE_EQ(config.drained_walls[0].pore_pressure, 500);
  EXPECT_DOUBLE_EQ(config.soils.at(0).damping, 0);  // off by default
}

TEST(SoilCases, LiakopoulosCaseFollowsTable1) {
  const pb::ScenarioSpec spec = load_case_file(kCases + "liakopoulos.yaml");
  const pb::SoilModel& soil = spec.materials(0).soil();
  EXPECT_DOUBLE_EQ(soil.grain_density(), 2000);
  EXPECT_DOUBLE_EQ(soil.porosity(), 0.2975);
  EXPECT_DOUBLE_EQ(soil.water_bulk_modulus(), 2e6);
  EXPECT_DOUBLE_EQ(soil.saturated_conductivity(), 4.41e-6);
  EXPECT_DOUBLE_EQ(soil.mechanical().linear_elastic().youngs_modulus(), 1.3e6);
  EXPECT_DOUBLE_EQ(soil.mechanical().linear_elastic().poisson_ratio(), 0.4);
  EXPECT_TRUE(soil.hydraulic().has_liakopoulos());
  EXPECT_DOUBLE_EQ(soil.damping(), 0.1);
  EXPECT_DOUBLE_EQ(spec.dp(), 0.02);
  ASSERT_TRUE(spec.bodies(0).has_pore_pressure());
  EXPECT_DOUBLE_EQ(spec.bodies(0).pore_pressure(), 0);
  EXPECT_DOUBLE_EQ(spec.initialisation().duration(), 20);
  EXPECT_TRUE(spec.initialisation().hydraulics().has_surface_pressure());
  EXPECT_FALSE(spec.hydraulics().has_surface_pressure());
  EXPECT_DOUBLE_EQ(spec.hydraulics().rainfall_intensity(), 0);
  EXPECT_EQ(spec.probes(0).field(), "pore_pressure");
  EXPECT_EQ(spec.probes(1).field(), "displacement_z");
  // The periodic width spans 6.3 h down to dp = 0.05, in whole spacings of 0.02, 0.025 and 0.05.
  const double width = spec.domain().max(0) - spec.domain().min(0);
  EXPECT_GE(width, 6.3 * 1.3 * 0.05);
  for (double dp : {0.02, 0.025, 0.05}) EXPECT_NEAR(std::remainder(width, dp), 0.0, 1e-12) << dp;
}

TEST(SoilErrors, SoilProbes) {
  expect_error(soil_with_line(32, "  - {name: p, kind: point, field: saturation, position: [0.12, 0.5]}"),
               {"probes[0].phase", 32, "'saturation' is a field of soil particles: give phase: soil"});
  expect_error(soil_with_line(32, "  - {name: p, kind: max, field: seepage_y, phase: soil}"),
               {"probes[0].field", 32, "'seepage_y' is not a field"});
  expect_error(soil_with_line(32, "  - {name: p, kind: max, field: suction, phase: soil}"),
               {"probes[0].field", 32, "'suction' is not a field"});
  // Every field the probe sampler is getting is accepted.
  for (const char* field :
       {"pore_pressure", "saturation", "porosity", "plastic_strain", "seepage_x", "seepage_z", "displacement_x",
        "displacement_z", "stress_xx", "stress_yy", "stress_zz", "stress_xy", "stress_yz", "stress_zx",
        "effective_stress_xx", "effective_stress_yy", "effective_stress_zz", "effective_stress_xy",
        "effective_stress_yz", "effective_stress_zx", "free_surface"}) {
    SCOPED_TRACE(field);
    EXPECT_NO_THROW(load_case_text(
        soil_with_line(32, std::string("  - {name: p, kind: mean, phase: soil, field: ") + field + "}")));
  }
}

}  // namespace
}  // namespace cascade

// --- Snapshots (output.snapshots) ---------------------------------------------------------------

namespace cascade {

namespace {

// The base case with one snapshot at line 27.
std::string with_snapshot(const std::string& snapshot) {
  return base() + "output:\n  snapshots:\n    - " + snapshot + "\n";
}

}  // namespace

TEST(CaseSnapshots, DefaultsAreApplied) {
  const v1::ScenarioSpec spec = load_case_text(with_snapshot("{field: pressure}"), {}, "test.yaml");
  ASSERT_EQ(spec.output().snapshots_size(), 1);
  const v1::Snapshot& s = spec.output().snapshots(0);
  EXPECT_EQ(s.name(), "pressure");
  EXPECT_EQ(s.camera(), "side");
  EXPECT_EQ(s.colour_map(), "viridis");
  EXPECT_EQ(s.width(), 1280);
  EXPECT_EQ(s.height(), 720);
  const v1::ScenarioSpec phases = load_case_text(with_snapshot("{}"), {}, "test.yaml");
  EXPECT_EQ(phases.output().snapshots(0).field(), "phase");
  EXPECT_EQ(phases.output().snapshots(0).name(), "phase");
}

TEST(CaseSnapshots, BadValuesNameTheKey) {
  expect_error(with_snapshot("{field: temperature}"),
               {"output.snapshots[0].field", 28, "'temperature' is not a field a snapshot can show"});
  expect_error(with_snapshot("{field: pore_pressure}"),
               {"output.snapshots[0].field", 28, "is a field of soil particles, and the case has no soil"});
  expect_error(with_snapshot("{field: velocity_y}"), {"output.snapshots[0].field", 28, "is not a field"});
  expect_error(with_snapshot("{width: 3841}"), {"output.snapshots[0].width", 28, "must be in [1, 3840] pixels"});
  expect_error(with_snapshot("{height: 2161}"), {"output.snapshots[0].height", 28, "must be in [1, 2160] pixels"});
  expect_error(with_snapshot("{camera: orbit}"), {"output.snapshots[0].camera", 28, "a 2D case is drawn in its x-z plane"});
  expect_error(with_snapshot("{phase: mud}"), {"output.snapshots[0].phase", 28, "'mud' is not a phase"});
  expect_error(with_snapshot("{translucent: [air]}"), {"output.snapshots[0].translucent[0]", 28, "'air' is not a phase"});
  expect_error(with_snapshot("{colour_map: jet}"), {"output.snapshots[0].colour_map", 28, "'jet' is not a colour map"});
  expect_error(with_snapshot("{field: pressure, min: 5, max: 1}"), {"output.snapshots[0].max", 28, "must be greater than min"});
  expect_error(with_snapshot("{slab: {axis: y, thickness: 0.1}}"),
               {"output.snapshots[0].slab.axis", 28, "'y' is not an axis of this case (x, z)"});
  expect_error(with_snapshot("{background: [1, 2, 0]}"), {"output.snapshots[0].background[1]", 28, "must be in [0, 1]"});
  expect_error(with_snapshot("{field: pressure}\n    - {field: pressure}"),
               {"output.snapshots[1].name", 29, "'pressure' is already the name of output.snapshots[0]"});
}

}  // namespace cascade

namespace cascade {
namespace {

// The cascade's event criteria (scenario.proto, CascadeEvents): thresholds > 0, a gauge is an
// elevation probe, each needs the phases it watches.
TEST(CascadeEventErrors, EachBadCriterionNamesItsKey) {
  expect_error(base() + "events: {ponding_started: true}\n",
               {"events.ponding_started", 26, "the case has no soil material"});
  expect_error(soil_base() + "events: {landslide_onset: {plastic_strain: 0.05, speed: 0, volume: 0.01}}\n",
               {"events.landslide_onset.speed", 33, "must be greater than 0"});
  expect_error(soil_base() + "events: {water_impact: {speed: 0.1}}\n",
               {"events.water_impact", 33, "needs soil and water"});
  expect_error(base() + "events: {wave_at_gauge: [{probe: p, rise: 0.01}]}\n",
               {"events.wave_at_gauge[0].probe", 26, "'p' is not the name of an elevation probe"});
  expect_error(base() + "  - {name: g, kind: elevation, position: [0.5]}\n"
                        "events: {wave_at_gauge: [{probe: g, rise: -1}]}\n",
               {"events.wave_at_gauge[0].rise", 27, "must be greater than 0"});
  expect_error(base() + "events: {overtopping: [{name: bank, axis: z, position: 1, above: 0.5}]}\n",
               {"events.overtopping[0].axis", 26, "'z' is not a horizontal axis"});
  const pb::ScenarioSpec spec =
      load_case_text(base() + "events: {overtopping: [{name: bank, axis: x, position: 0.9, above: 0.4}]}\n");
  EXPECT_EQ(spec.events().overtopping(0).name(), "bank");
}

}  // namespace
}  // namespace cascade
