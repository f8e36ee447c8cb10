// Case files → ScenarioSpec: the shipped cases load with their defaults, overrides apply, and every
// kind of mistake is a CaseError that names the key and its line.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "server/scenario/case_loader.h"

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
  expect_error(base(), {"dp", -1, "expected a number, got 'abc' (from --set dp=abc)"}, {parse_override("dp=abc")});
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

}  // namespace
}  // namespace cascade
