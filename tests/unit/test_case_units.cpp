// Units in case files and hyetographs: every unit converts by its exact factor,
// the schema's `unit` option decides which fields take which units, a
// hyetograph CSV becomes the `rainfall` series, and every mistake is a
// CaseError that names the key, its line and (for a CSV) the file and row.
#include <google/protobuf/descriptor.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "server/scenario/case_loader.h"
#include "server/scenario/case_units.h"
#include "server/scenario/soil_setup.h"

namespace cascade {
namespace {

namespace pb = cascade::v1;
namespace fs = std::filesystem;

const std::string kCases = std::string(CASCADE_SOURCE_DIR) + "/cases/";

// A small rigid soil column under rain; the tests replace one line at a time
// (1-based).
const std::vector<std::string> kColumn = {
    "dimensions: 2",                                                       // 1
    "dp: 0.1",                                                             // 2
    "h_over_dp: 1.8",                                                      // 3
    "end_time: 600",                                                       // 4
    "domain: {min: [0, -0.4], max: [1.2, 1.1], periodic: [true, false]}",  // 5
    "gravity: [0, -9.81]",                                                 // 6
    "materials:",                                                          // 7
    "  - name: column",                                                    // 8
    "    soil:",                                                           // 9
    "      grain_density: 2650",                                           // 10
    "      porosity: 0.4",                                                 // 11
    "      saturated_conductivity: 1e-4",                                  // 12
    "      water_bulk_modulus: 2e6",                                       // 13
    "      rigid: true",                                                   // 14
    "      hydraulic: {gardner: {s_min: 0.23, s_max: 1.0, alpha: 2.0}}",   // 15
    "bodies:",                                                             // 16
    "  - {name: base, kind: boundary, shape: {box: {min: [0, -0.4], max: [1.2, "
    "0]}}}",                                             // 17
    "  - name: column",                                  // 18
    "    kind: fluid",                                   // 19
    "    material: column",                              // 20
    "    shape: {box: {min: [0, 0], max: [1.2, 1.0]}}",  // 21
    "    initial: {water_table: 0.0}",                   // 22
    "hydraulics:",                                       // 23
    "  rainfall_intensity: 1e-6",                        // 24
    "  ponding_pressure: 0",                             // 25
};

std::string column_with(const std::vector<std::pair<int, std::string>> &replacements) {
  std::vector<std::string> lines = kColumn;
  for (const auto &[n, text] : replacements) lines.at(n - 1) = text;
  std::string text;
  for (const std::string &line : lines) text += line + "\n";
  return text;
}

std::string column_with(int n, const std::string &line) { return column_with({{n, line}}); }

struct Expected {
  std::string key;
  int line;             // in the case file; -1: none
  std::string message;  // a part of what()
};

void expect_error(const std::function<void()> &load, const Expected &expected) {
  try {
    load();
    ADD_FAILURE() << "no CaseError; expected one for key '" << expected.key << "'";
  } catch (const CaseError &e) {
    const std::string what = e.what();
    EXPECT_EQ(e.key(), expected.key) << what;
    EXPECT_EQ(e.line(), expected.line) << what;
    EXPECT_NE(what.find("key '" + expected.key + "': "), std::string::npos) << what;
    EXPECT_NE(what.find(expected.message), std::string::npos) << what;
  }
}

void expect_text_error(const std::string &text, const Expected &expected,
                       const std::vector<CaseOverride> &overrides = {}) {
  expect_error([&] { load_case_text(text, overrides, "test.yaml"); }, expected);
}

// --- The unit table
// --------------------------------------------------------------------------

struct UnitValue {
  const char *unit;
  double value;
  const char *si;
  double expected;  // the SI value, exact as a decimal: the double nearest to it
                    // must come out
};

TEST(CaseUnits, EveryUnitConvertsByItsExactFactor) {
  const UnitValue table[] = {
      {"s", 7, "s", 7},
      {"min", 2.5, "s", 150},
      {"h", 36, "s", 129600},
      {"day", 1.5, "s", 129600},
      {"d", 2, "s", 172800},
      {"m/s", 0.25, "m/s", 0.25},
      {"mm/h", 45, "m/s", 1.25e-5},
      {"mm/day", 864, "m/s", 1e-5},
      {"cm/h", 36, "m/s", 1e-4},
      {"m/h", 36, "m/s", 0.01},
      {"m/day", 864, "m/s", 0.01},
      {"Pa", 12.5, "Pa", 12.5},
      {"kPa", 2.5, "Pa", 2500},
      {"MPa", 1.5, "Pa", 1.5e6},
      {"GPa", 0.5, "Pa", 5e8},
      {"m", 3, "m", 3},
      {"cm", 2, "m", 0.02},
      {"mm", 20, "m", 0.02},
      {"km", 1.5, "m", 1500},
      {"m/s^2", 9.81, "m/s^2", 9.81},
      {"kg/m^3", 1000, "kg/m^3", 1000},
      {"1/m", 2, "1/m", 2},
  };
  for (const UnitValue &u : table) {
    const CaseUnit *unit = find_case_unit(u.unit);
    ASSERT_NE(unit, nullptr) << u.unit;
    EXPECT_STREQ(unit->si, u.si) << u.unit;
    EXPECT_EQ(unit->to_si(u.value), u.expected) << u.value << " " << u.unit;
  }
  EXPECT_EQ(find_case_unit("m/day")->to_si(1),
            1.0 / 86400);  // K_sat of Section 4.1
  EXPECT_EQ(find_case_unit("mm/hr"), nullptr);
  EXPECT_EQ(find_case_unit("MM/H"),
            nullptr);  // unit names are case-sensitive (mPa is not MPa)
  EXPECT_EQ(unit_names("s"), "s, min, h, day, d");
  EXPECT_EQ(unit_names("m/s"), "m/s, mm/h, mm/day, cm/h, m/h, m/day");
  EXPECT_EQ(unit_names("Pa"), "Pa, kPa, MPa, GPa");
  EXPECT_EQ(unit_names("m"), "m, cm, mm, km");
}

TEST(CaseUnits, NumberAndUnitAreSplitAtSpaces) {
  const auto given = split_number_with_unit("4.5e1  mm/h");
  ASSERT_TRUE(given);
  EXPECT_EQ(given->number, 45);
  EXPECT_EQ(given->unit, "mm/h");
  EXPECT_FALSE(split_number_with_unit("45mm/h"));
  EXPECT_FALSE(split_number_with_unit("45"));
  EXPECT_FALSE(split_number_with_unit("45 "));
  EXPECT_FALSE(split_number_with_unit("h 36"));
  EXPECT_FALSE(split_number_with_unit(" 36 h"));
}

// Every double field of the schema that names a unit names one of the table's
// SI units; the time fields of the stages have one; angles and ratios have
// none.
TEST(CaseUnits, SchemaFieldsNameKnownSiUnits) {
  std::set<const google::protobuf::Descriptor *> seen;
  int annotated = 0;
  std::function<void(const google::protobuf::Descriptor *)> visit = [&](const google::protobuf::Descriptor *d) {
    if (!seen.insert(d).second) return;
    for (int i = 0; i < d->field_count(); ++i) {
      const google::protobuf::FieldDescriptor *f = d->field(i);
      const std::string si = si_unit_of(f);
      if (!si.empty()) {
        ++annotated;
        EXPECT_EQ(f->cpp_type(), google::protobuf::FieldDescriptor::CPPTYPE_DOUBLE) << f->full_name();
        EXPECT_FALSE(dimension_name(si).empty()) << f->full_name() << " names '" << si << "'";
        EXPECT_STREQ(find_case_unit(si)->si, si.c_str()) << f->full_name();
      }
      if (f->message_type() != nullptr) visit(f->message_type());
    }
  };
  visit(pb::ScenarioSpec::descriptor());
  EXPECT_GE(annotated, 60);
  const auto unit_of = [](const google::protobuf::Descriptor *d, const char *name) {
    return si_unit_of(d->FindFieldByName(name));
  };
  EXPECT_EQ(unit_of(pb::ScenarioSpec::descriptor(), "end_time"), "s");
  EXPECT_EQ(unit_of(pb::Stage::descriptor(), "output_interval"), "s");
  EXPECT_EQ(unit_of(pb::Stage::descriptor(), "probe_interval"), "s");
  EXPECT_EQ(unit_of(pb::StageEnd::descriptor(), "time"), "s");
  EXPECT_EQ(unit_of(pb::PoreWaterStage::descriptor(), "max_dt"), "s");
  EXPECT_EQ(unit_of(pb::PoreWaterStage::descriptor(), "pressure_tolerance"), "Pa");
  EXPECT_EQ(unit_of(pb::HydraulicBoundary::descriptor(), "rainfall_intensity"), "m/s");
  EXPECT_EQ(unit_of(pb::SoilModel::descriptor(), "saturated_conductivity"), "m/s");
  EXPECT_EQ(unit_of(pb::GardnerModel::descriptor(), "alpha"), "1/m");
  EXPECT_EQ(unit_of(pb::DruckerPragerModel::descriptor(), "friction_angle"),
            "");  // degrees, plain
  EXPECT_EQ(unit_of(pb::SoilModel::descriptor(), "porosity"), "");
  EXPECT_EQ(unit_of(pb::YieldBand::descriptor(), "volume"),
            "");  // m³ in 3D, m² in 2D
}

// --- Units in case files
// -----------------------------------------------------------------------

TEST(CaseUnitFields, ValuesWithUnitsLoadInSi) {
  const pb::ScenarioSpec spec = load_case_text(column_with({
      {2, "dp: 10 cm"},
      {4, "end_time: \"36 h\""},  // quoted: the same text
      {5,
       "domain: {min: [0 m, -40 cm], max: [1200 mm, 1.1], periodic: [true, "
       "false]}"},
      {12, "      saturated_conductivity: 1 m/day"},
      {13, "      water_bulk_modulus: 2 MPa"},
      {15, "      hydraulic: {gardner: {s_min: 0.23, s_max: 1.0, alpha: 2 1/m}}"},
      {22, "    initial: {water_table: 50 cm}"},
      {24, "  rainfall_intensity: 45 mm/h"},
      {25, "  ponding_pressure: 2 kPa"},
  }));
  EXPECT_EQ(spec.dp(), 0.1);
  EXPECT_EQ(spec.end_time(), 129600);
  EXPECT_EQ(spec.domain().min(1), -0.4);
  EXPECT_EQ(spec.domain().max(0), 1.2);
  EXPECT_EQ(spec.domain().max(1), 1.1);
  EXPECT_EQ(spec.materials(0).soil().saturated_conductivity(), 1.0 / 86400);
  EXPECT_EQ(spec.materials(0).soil().water_bulk_modulus(), 2e6);
  EXPECT_EQ(spec.materials(0).soil().hydraulic().gardner().alpha(), 2);
  EXPECT_EQ(spec.bodies(1).initial().water_table(), 0.5);
  EXPECT_EQ(spec.hydraulics().rainfall_intensity(), 1.25e-5);
  EXPECT_EQ(spec.hydraulics().ponding_pressure(), 2000);
  EXPECT_EQ(spec.output().interval(),
            1296);  // the default, end_time / 100, from the SI end time
}

TEST(CaseUnitFields, StagesAndPolygonVerticesTakeUnits) {
  const pb::ScenarioSpec spec = load_case_text(column_with({
      {21,
       "    shape: {polygon: {vertices: [[0, 0], [120 cm, 0], [1.2, 1000 "
       "mm], [0, 1]]}}"},
      {25,
       "  ponding_pressure: 0\n"
       "stages:\n"
       "  - {pore_water: {initial_dt: 1 min, max_dt: 1 h, "
       "pressure_tolerance: 5 Pa}, end: {time: 6 h},\n"
       "     output_interval: 30 min, probe_interval: 5 min}\n"
       "  - {dynamic: {}}"},
  }));
  EXPECT_EQ(spec.bodies(1).shape().polygon().vertices(1).x(), 1.2);
  EXPECT_EQ(spec.bodies(1).shape().polygon().vertices(2).z(), 1.0);
  const pb::Stage &stage = spec.stages(0);
  EXPECT_EQ(stage.pore_water().initial_dt(), 60);
  EXPECT_EQ(stage.pore_water().max_dt(), 3600);
  EXPECT_EQ(stage.pore_water().pressure_tolerance(), 5);
  ASSERT_TRUE(stage.end().has_time());
  EXPECT_EQ(stage.end().time(), 21600);
  EXPECT_EQ(stage.output_interval(), 1800);
  EXPECT_EQ(stage.probe_interval(), 300);
}

TEST(CaseUnitFields, OverridesTakeUnits) {
  const pb::ScenarioSpec spec =
      load_case_text(column_with(4, "end_time: 600"),
                     {parse_override("end_time=2 day"), parse_override("hydraulics.rainfall_intensity = 45 mm/h"),
                      parse_override("domain.max=[1.2 m, 110 cm]")});
  EXPECT_EQ(spec.end_time(), 172800);
  EXPECT_EQ(spec.hydraulics().rainfall_intensity(), 1.25e-5);
  EXPECT_EQ(spec.domain().max(1), 1.1);
}

TEST(CaseUnitErrors, UnknownUnit) {
  expect_text_error(column_with(24, "  rainfall_intensity: 45 mm/hr"),
                    {"hydraulics.rainfall_intensity", 24,
                     "unknown unit 'mm/hr' (units of a speed: m/s, mm/h, "
                     "mm/day, cm/h, m/h, m/day)"});
}

TEST(CaseUnitErrors, UnitOfTheWrongDimension) {
  expect_text_error(column_with(24, "  rainfall_intensity: 45 mm"),
                    {"hydraulics.rainfall_intensity", 24, "takes a speed (m/s); 'mm' is a length"});
  expect_text_error(column_with(4, "end_time: 3 kPa"), {"end_time", 4, "takes a time (s); 'kPa' is a pressure"});
  expect_text_error(column_with(13, "      water_bulk_modulus: 2 h"),
                    {"materials[0].soil.water_bulk_modulus", 13, "takes a pressure (Pa); 'h' is a time"});
}

TEST(CaseUnitErrors, UnitOnAFieldWithoutDimension) {
  expect_text_error(column_with(11, "      porosity: 0.4 m"),
                    {"materials[0].soil.porosity", 11, "takes a plain number without a unit, got '0.4 m'"});
  expect_text_error(column_with(3, "h_over_dp: 1.8 cm"), {"h_over_dp", 3, "takes a plain number without a unit"});
}

TEST(CaseUnitErrors, MalformedNumberWithUnit) {
  expect_text_error(column_with(4, "end_time: 36h"), {"end_time", 4,
                                                      "expected a number, got '36h' (or a number and a unit of "
                                                      "a time: s, min, h, day, d)"});
  expect_text_error(column_with(4, "end_time: h 36"), {"end_time", 4, "expected a number, got 'h 36'"});
  expect_text_error(column_with(13, "      water_bulk_modulus: 1e300 GPa"),
                    {"materials[0].soil.water_bulk_modulus", 13, "expected a finite number, got '1e300 GPa'"});
  expect_text_error(column_with(11, "      porosity: high"),
                    {"materials[0].soil.porosity", 11, "expected a number, got 'high'"});
}

TEST(CaseUnitErrors, InsideAListTheElementIsNamed) {
  expect_text_error(column_with(5,
                                "domain: {min: [0, -0.4], max: [1.2, 1.1 kPa], periodic: "
                                "[true, false]}"),
                    {"domain.max[1]", 5, "takes a length (m); 'kPa' is a pressure"});
}

TEST(CaseUnitErrors, OverrideNamesItself) {
  expect_text_error(column_with(4, "end_time: 600"), {"end_time", -1, "unknown unit 'fortnight' (units of a time"},
                    {parse_override("end_time=2 fortnight")});
  expect_text_error(column_with(4, "end_time: 600"), {"end_time", -1, "(from --set end_time=2 fortnight)"},
                    {parse_override("end_time=2 fortnight")});
}

// --- Hyetographs
// -------------------------------------------------------------------------------

// A fresh folder for a case file and its CSV files.
class Hyetographs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cascade_hyetograph_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string &name, const std::string &text) const {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name) << text;
  }

  // The column case with `line` as line 24 (the rain), written as DIR/case.yaml
  // and loaded.
  pb::ScenarioSpec load(const std::string &line, const std::vector<CaseOverride> &overrides = {}) const {
    return load({{24, line}}, overrides);
  }
  pb::ScenarioSpec load(const std::vector<std::pair<int, std::string>> &replacements,
                        const std::vector<CaseOverride> &overrides = {}) const {
    write("case.yaml", column_with(replacements));
    return load_case_file(case_path(), overrides);
  }
  void expect_load_error(const std::string &line, const Expected &expected,
                         const std::vector<CaseOverride> &overrides = {}) const {
    expect_error([&] { load(line, overrides); }, expected);
  }

  std::string case_path() const { return (dir_ / "case.yaml").string(); }
  std::string path(const std::string &name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

TEST_F(Hyetographs, ExpandIntoThePiecewiseConstantRainfallSeries) {
  write("storms/storm.csv",
        "# a test storm\n"
        "time_h, intensity_mm_per_h\n"
        "0, 0\n"
        "\n"
        "0.5, 45\r\n"  // spreadsheet line ends
        "1.25,9\n"
        "2, 0\n");
  const pb::ScenarioSpec spec = load(
      "  hyetograph: {file: storms/storm.csv, "
      "time_unit: h, intensity_unit: mm/h}");
  const pb::HydraulicBoundary &h = spec.hydraulics();
  EXPECT_FALSE(h.has_hyetograph());
  EXPECT_EQ(h.rainfall_file(), path("storms/storm.csv"));
  EXPECT_EQ(h.rainfall_intensity(), 0);
  ASSERT_EQ(h.rainfall_size(), 4);
  const double times[] = {0, 1800, 4500, 7200};
  const double intensities[] = {0, 1.25e-5, 2.5e-6, 0};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(h.rainfall(i).time(), times[i]) << i;
    EXPECT_EQ(h.rainfall(i).intensity(), intensities[i]) << i;
  }
  // Exactly as a `rainfall` series: each value from its time to the next one's.
  EXPECT_EQ(hydraulic_forcing(spec, 1799.9).rainfall_intensity, 0);
  EXPECT_EQ(hydraulic_forcing(spec, 1800).rainfall_intensity, 1.25e-5);
  EXPECT_EQ(hydraulic_forcing(spec, 4499).rainfall_intensity, 1.25e-5);
  EXPECT_EQ(hydraulic_forcing(spec, 4500).rainfall_intensity, 2.5e-6);
  EXPECT_EQ(hydraulic_forcing(spec, 1e6).rainfall_intensity, 0);
  // The same series written by hand in the case file gives the same spec.
  const pb::ScenarioSpec by_hand = load(
      "  rainfall: [{time: 0, intensity: 0}, {time: 30 min, intensity: 45 "
      "mm/h}, {time: 1.25 h, intensity: 9 mm/h},"
      " {time: 2 h, intensity: 0}]");
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(by_hand.hydraulics().rainfall(i).time(), h.rainfall(i).time());
    EXPECT_EQ(by_hand.hydraulics().rainfall(i).intensity(), h.rainfall(i).intensity());
  }
}

TEST_F(Hyetographs, SiUnitsWithoutHeaderAndAbsolutePath) {
  write("si.csv", "0,1e-6\n600,2e-6\n");
  const pb::ScenarioSpec spec = load("  hyetograph: {file: " + path("si.csv") + "}");
  ASSERT_EQ(spec.hydraulics().rainfall_size(), 2);
  EXPECT_EQ(spec.hydraulics().rainfall(1).time(), 600);
  EXPECT_EQ(spec.hydraulics().rainfall(1).intensity(), 2e-6);
  EXPECT_EQ(spec.hydraulics().rainfall_file(), path("si.csv"));
}

TEST_F(Hyetographs, OverrideNamesTheFile) {
  write("a.csv", "0,1e-6\n");
  write("b.csv", "0,3e-6\n");
  const pb::ScenarioSpec spec =
      load("  hyetograph: {file: a.csv}", {parse_override("hydraulics.hyetograph.file=b.csv")});
  EXPECT_EQ(spec.hydraulics().rainfall(0).intensity(), 3e-6);
}

TEST_F(Hyetographs, ShippedDesignStormLoads) {
  const pb::ScenarioSpec spec = load_case_file(
      kCases + "infiltration_1d.yaml", {parse_override("hydraulics.rainfall_intensity=0"),
                                        parse_override("hydraulics.hyetograph={file: storms/design_storm_24h.csv, "
                                                       "time_unit: h, intensity_unit: mm/h}")});
  const pb::HydraulicBoundary &h = spec.hydraulics();
  EXPECT_EQ(h.rainfall_file(), kCases + "storms/design_storm_24h.csv");
  ASSERT_EQ(h.rainfall_size(),
            49);  // 48 blocks of 30 min, then no rain from 24 h
  double depth = 0, peak = 0, peak_time = -1;
  for (int i = 0; i + 1 < h.rainfall_size(); ++i) {
    EXPECT_EQ(h.rainfall(i).time(), 1800.0 * i);
    depth += h.rainfall(i).intensity() * 1800;
    if (h.rainfall(i).intensity() > peak) peak = h.rainfall(i).intensity(), peak_time = h.rainfall(i).time();
  }
  EXPECT_EQ(h.rainfall(48).time(), 86400);
  EXPECT_EQ(h.rainfall(48).intensity(), 0);
  EXPECT_EQ(peak, 124.1 / 3.6e6);  // the file's comment: peak 124.1 mm/h at 11.5
                                   // h, 219.55 mm in all
  EXPECT_EQ(peak_time, 11.5 * 3600);
  EXPECT_NEAR(depth * 1000, 219.55, 1e-9);
}

TEST_F(Hyetographs, CsvErrorsNameKeyFileAndRow) {
  const std::string line = "  hyetograph: {file: storm.csv, time_unit: h, intensity_unit: mm/h}";
  const std::string key = "hydraulics.hyetograph.file";
  const std::string csv = path("storm.csv");
  expect_load_error(line, {key, 24, "cannot read the hyetograph " + csv});
  write("storm.csv", "time,intensity\n0,1\n1,abc\n");
  expect_load_error(line, {key, 24, csv + ":3: 'abc' is not a finite number"});
  write("storm.csv", "0,1\n2,1\n# comment\n1,1\n");
  expect_load_error(line, {key, 24, csv + ":4: the time 1 is not later than the time before it (2)"});
  write("storm.csv", "0,1\n0,2\n");
  expect_load_error(line, {key, 24, csv + ":2: the time 0 is not later than the time before it (0)"});
  write("storm.csv", "0,1\n1,-2\n");
  expect_load_error(line, {key, 24, csv + ":2: the intensity must not be negative (is -2)"});
  write("storm.csv", "-1,1\n");
  expect_load_error(line, {key, 24, csv + ":1: the time must not be negative (is -1)"});
  write("storm.csv", "0,1,2\n");
  expect_load_error(line, {key, 24, csv + ":1: expected two cells, time and intensity, got 3"});
  write("storm.csv", "time,intensity\nstart,1\n");
  expect_load_error(line, {key, 24, csv + ":2: 'start' is not a finite number"});
  write("storm.csv", "");
  expect_load_error(line, {key, 24, csv + ": has no rows of time and intensity"});
  write("storm.csv", "# only a comment\ntime,intensity\n");
  expect_load_error(line, {key, 24, csv + ": has no rows of time and intensity"});
}

TEST_F(Hyetographs, SchemaErrors) {
  write("storm.csv", "0,1\n");
  expect_load_error("  hyetograph: {file: storm.csv, time_unit: mm/h}",
                    {"hydraulics.hyetograph.time_unit", 24, "takes a time (s); 'mm/h' is a speed"});
  expect_load_error("  hyetograph: {file: storm.csv, intensity_unit: mm/hr}",
                    {"hydraulics.hyetograph.intensity_unit", 24, "unknown unit 'mm/hr' (units of a speed"});
  expect_load_error("  hyetograph: {time_unit: h}", {"hydraulics.hyetograph.file", 24, "is missing"});
  expect_load_error("  rainfall_intensity: 1e-6\n  hyetograph: {file: storm.csv}",
                    {"hydraulics.hyetograph", 25, "cannot be given together with rainfall_intensity or rainfall"});
  expect_load_error(
      "  rainfall: [{time: 0, intensity: 1e-6}]\n  hyetograph: {file: "
      "storm.csv}",
      {"hydraulics.hyetograph", 25, "cannot be given together with rainfall_intensity or rainfall"});
  expect_load_error("  rainfall_file: x.csv\n  hyetograph: {file: storm.csv}",
                    {"hydraulics.rainfall_file", 24, "is set by the loader from hyetograph.file"});
  expect_load_error("  hyetograph: {file: storm.csv}\n  surface_pressure: 0",
                    {"hydraulics.surface_pressure", 25, "leave out rainfall_intensity, rainfall and hyetograph"});
}

TEST_F(Hyetographs, InitialisationHoldsConstantConditions) {
  write("storm.csv", "0,1\n");
  expect_error(
      [&] {
        load({{25,
               "  ponding_pressure: 0\n"
               "initialisation: {duration: 10, hydraulics: {hyetograph: "
               "{file: storm.csv}}}"}});
      },
      {"initialisation.hydraulics.hyetograph", 26, "is a time series"});
}

// The server loads case text and specs; it reads no files that a request names.
TEST_F(Hyetographs, CaseTextAndSpecsWithAHyetographAreRefused) {
  write("storm.csv", "0,1\n");
  expect_text_error(column_with(24, "  hyetograph: {file: " + path("storm.csv") + "}"),
                    {"hydraulics.hyetograph", 24, "names a file, which only the loader of a case file reads"});
  pb::ScenarioSpec spec = load_case_text(column_with({}));
  spec.mutable_hydraulics()->set_rainfall_intensity(0);
  spec.mutable_hydraulics()->mutable_hyetograph()->set_file(path("storm.csv"));
  expect_error([&] { validate_spec(spec); }, {"hydraulics.hyetograph", -1, "names a file"});
  spec.mutable_hydraulics()->clear_hyetograph();
  spec.mutable_hydraulics()->set_rainfall_file("storm.csv");
  expect_error([&] { validate_spec(spec); }, {"hydraulics.rainfall_file", -1, "there is no series"});
  // An expanded spec, as `cascade create` sends it, passes.
  const pb::ScenarioSpec expanded = load("  hyetograph: {file: storm.csv}");
  EXPECT_NO_THROW(validate_spec(expanded));
}

}  // namespace
}  // namespace cascade
