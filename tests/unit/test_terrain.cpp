// Terrain from elevation rasters (docs/cases.md, "Terrain"): the GeoTIFF reader against the
// analytic hillside it was written from (tools/terrain/hillside.h), the builder's particles
// against the raster surface and base, the 2D section against the 3D window's middle slice, the
// lake, the shipped cases (the 3D one with its house from an STL file), and every bad input's error
// naming its key and file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include "cascade/v1/scenario.pb.h"
#include "server/scenario/case_error.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/particle_builder.h"
#include "tests/unit/scratch_folder.h"
#include "server/terrain/raster.h"
#include "tools/terrain/hillside.h"

namespace cascade {
namespace {

namespace fs = std::filesystem;
namespace hs = hillside;

const std::string kTerrain = std::string(CASCADE_SOURCE_DIR) + "/cases/terrain/";
const std::string kSurface = kTerrain + "hillside_surface.tif";
const std::string kBedrock = kTerrain + "hillside_bedrock.tif";

// The raster's bilinear interpolation of a smooth surface z differs from it by at most
// (max |z_xx| + max |z_yy|) pixel² / 8; the bound for the two hillside surfaces, from their second
// differences over the raster at 0.25 m (about 0.029 m: the far bank's tanh), plus Float32's
// rounding at 130 m (1e-5 m).
double interpolation_bound() {
  const double e = 1e-3;
  double bound = 0.0;
  for (double (*z)(double, double) : {&hs::surface, &hs::bedrock}) {
    double zxx = 0.0, zyy = 0.0;
    for (double u = 0.0; u <= hs::kWidth; u += 0.25)
      for (double v = 0.0; v <= hs::kHeight; v += 0.25) {
        const double x = hs::kX0 + u, y = hs::kY0 + v, c = z(x, y);
        zxx = std::max(zxx, std::abs(z(x + e, y) - 2 * c + z(x - e, y)) / (e * e));
        zyy = std::max(zyy, std::abs(z(x, y + e) - 2 * c + z(x, y - e)) / (e * e));
      }
    bound = std::max(bound, (zxx + zyy) * hs::kPixel * hs::kPixel / 8.0);
  }
  return bound + 1e-5;
}
const double kInterpolation = interpolation_bound();

// A scratch folder for this file's cases and inputs.
class Scratch : public testing::ScratchFolder {
 public:
  Scratch() : ScratchFolder("cascade_terrain") {}
};

// A case on the hillside: bedrock, colluvium and a lake at 102 m, `terrain` the YAML of its
// terrain section's inner keys, the domain the footprint (elevations 96–130 m): the bedrock's sides
// face out of it, so that only its top has dummy layers.
std::string hillside_case(int dimensions, double dp, const std::string& terrain, double length, double width = 0) {
  std::ostringstream c;
  c << "name: hillside\ndimensions: " << dimensions << "\ndp: " << dp << "\nend_time: 1\n";
  c << "terrain: {" << terrain << "}\n";
  if (dimensions == 3)
    c << "domain: {min: [0, 0, 96], max: [" << length << ", " << width << ", 130]}\ngravity: [0, 0, -9.81]\n";
  else
    c << "domain: {min: [0, 96], max: [" << length << ", 130]}\ngravity: [0, -9.81]\n";
  c << R"(materials:
  - {name: water, water: {density: 1000, max_speed: 10}}
  - name: sand
    soil:
      grain_density: 2690
      porosity: 0.3
      saturated_conductivity: 1e-4
      hydraulic: {van_genuchten: {s_min: 0.087, s_max: 1.0, lambda: 0.61, p_ref: 4350}}
      mechanical: {drucker_prager: {youngs_modulus: 6e6, poisson_ratio: 0.3, cohesion: 6e3, friction_angle: 34}}
bodies:
  - {name: bedrock, kind: boundary, shape: {terrain: {layer: bedrock}}}
  - {name: colluvium, kind: fluid, material: sand, shape: {terrain: {layer: ground}}, initial: {suction: 7e3}}
  - {name: lake, kind: fluid, material: water, shape: {terrain: {layer: lake, level: 102}}}
)";
  return c.str();
}

std::string window(double x0, double y0, double x1, double y1) {
  std::ostringstream w;
  w.precision(12);
  w << "window: {min: [" << x0 << ", " << y0 << "], max: [" << x1 << ", " << y1 << "]}";
  return w.str();
}

std::string files(const std::string& surface = kSurface, const std::string& base = "base_file: " + kBedrock) {
  return "surface_file: " + surface + ", " + base + ", ";
}

struct Column {
  double bottom = 1e300, top = -1e300;  // lowest and highest particle centre
  int count = 0;
};

// Per lattice column (x index, y index) of one phase: its lowest and highest particle.
std::map<std::pair<long, long>, Column> columns(const HostParticles& p, Phase phase, double dp) {
  std::map<std::pair<long, long>, Column> out;
  const int d = p.dimensions;
  for (std::size_t n = 0; n < p.size(); ++n) {
    if (p.phase[n] != phase) continue;
    const long i = std::lround(p.position[n * d] / dp - 0.5), j = d == 3 ? std::lround(p.position[n * d + 1] / dp - 0.5) : 0;
    Column& c = out[{i, j}];
    const double z = p.position[n * d + d - 1];
    c.bottom = std::min(c.bottom, z), c.top = std::max(c.top, z), ++c.count;
  }
  return out;
}

TEST(TerrainRaster, ReadsPixelCentresAndInterpolatesBilinearly) {
  const Raster r = Raster::open(kSurface, {hs::kX0, hs::kY0, hs::kX0 + hs::kWidth, hs::kY0 + hs::kHeight});
  const auto e = r.extent();
  EXPECT_DOUBLE_EQ(e[0], hs::kX0);
  EXPECT_DOUBLE_EQ(e[1], hs::kY0);
  EXPECT_DOUBLE_EQ(e[2], hs::kX0 + hs::kWidth);
  EXPECT_DOUBLE_EQ(e[3], hs::kY0 + hs::kHeight);
  EXPECT_NE(r.crs().find("Hong Kong 1980"), std::string::npos) << r.crs();
  // At pixel centres: the analytic value as Float32 stores it.
  for (double x : {0.5, 37.5, 80.5, 159.5})
    for (double y : {0.5, 40.5, 79.5})
      EXPECT_NEAR(*r.at(hs::kX0 + x, hs::kY0 + y), hs::surface(hs::kX0 + x, hs::kY0 + y), 2e-5) << x << ", " << y;
  // Between four centres: their mean.
  const double x = hs::kX0 + 80.0, y = hs::kY0 + 40.0;
  const double mean = 0.25 * (*r.at(x - 0.5, y - 0.5) + *r.at(x + 0.5, y - 0.5) + *r.at(x - 0.5, y + 0.5) + *r.at(x + 0.5, y + 0.5));
  EXPECT_NEAR(*r.at(x, y), mean, 1e-9);
  EXPECT_FALSE(r.at(hs::kX0 - 0.1, y));
  EXPECT_FALSE(r.at(x, hs::kY0 + hs::kHeight + 0.1));
}

// 1,000 columns of a 3D window: the top soil particle lies within dp/2 of the raster surface
// (its cell's top, centre + dp/2, within dp/2 of the surface at the column's map point) and the
// lowest within dp/2 of the bedrock raster, so the soil's thickness is the rasters' difference.
TEST(TerrainBuilder, ParticlesFollowTheSurfaceAndBaseRasters3D) {
  Scratch scratch;
  const double dp = 0.5, x0 = hs::kX0 + 40.0, y0 = hs::kY0 + 25.0;
  const std::string path =
      scratch.write("window.yaml", hillside_case(3, dp, files() + window(x0, y0, x0 + 80.0, y0 + 30.0), 80.0, 30.0));
  const ParticleSet set = build_particle_set(load_case_file(path));
  const auto soil = columns(set.particles, Phase::soil, dp);
  ASSERT_EQ(soil.size(), 160u * 60u);  // every column of the window has soil
  std::vector<std::pair<long, long>> keys;
  for (const auto& [key, c] : soil) keys.push_back(key);
  std::mt19937 random(7);
  std::shuffle(keys.begin(), keys.end(), random);
  double worst_top = 0.0, worst_bottom = 0.0;
  for (std::size_t k = 0; k < 1000; ++k) {
    const auto [i, j] = keys[k];
    const Column& c = soil.at(keys[k]);
    const double x = x0 + (i + 0.5) * dp, y = y0 + (j + 0.5) * dp;
    worst_top = std::max(worst_top, std::abs(c.top + 0.5 * dp - hs::surface(x, y)));
    worst_bottom = std::max(worst_bottom, std::abs(c.bottom - 0.5 * dp - hs::bedrock(x, y)));
    EXPECT_EQ(c.count, long(std::lround((c.top - c.bottom) / dp)) + 1) << "a gap in column " << i << ", " << j;
  }
  EXPECT_LE(worst_top, 0.5 * dp + kInterpolation);
  EXPECT_LE(worst_bottom, 0.5 * dp + kInterpolation);
  // The bedrock's dummy layers lie under the soil: none above a column's lowest soil particle.
  const auto rock = columns(set.particles, Phase::boundary, dp);
  for (const auto& [key, c] : soil)
    if (rock.count(key)) EXPECT_LT(rock.at(key).top, c.bottom) << key.first << ", " << key.second;
}

// The section along a straight polyline at the map Y of a lattice row of the window gives the
// window's particles in that row: the same x and z for the soil, the lake and their counts.
TEST(TerrainBuilder, SectionEqualsTheWindowsMiddleSlice) {
  Scratch scratch;
  const double dp = 0.5, x0 = hs::kX0 + 10.0, y0 = hs::kY0 + 30.0, length = 100.0, width = 20.0;
  const int row = 19;  // y = 9.75 m, the middle of the 20 m window
  const double y_row = y0 + (row + 0.5) * dp;
  std::ostringstream section;
  section.precision(12);
  section << "section: [{x: " << x0 << ", y: " << y_row << "}, {x: " << x0 + length << ", y: " << y_row << "}]";
  const ParticleSet window3d = build_particle_set(load_case_file(
      scratch.write("window.yaml", hillside_case(3, dp, files() + window(x0, y0, x0 + length, y0 + width), length, width))));
  const ParticleSet section2d =
      build_particle_set(load_case_file(scratch.write("section.yaml", hillside_case(2, dp, files() + section.str(), length))));
  for (Phase phase : {Phase::soil, Phase::water}) {
    std::multiset<std::pair<double, double>> slice, cut;
    const HostParticles &p3 = window3d.particles, &p2 = section2d.particles;
    for (std::size_t n = 0; n < p3.size(); ++n)
      if (p3.phase[n] == phase && p3.position[3 * n + 1] == (row + 0.5) * dp)
        slice.insert({p3.position[3 * n], p3.position[3 * n + 2]});
    for (std::size_t n = 0; n < p2.size(); ++n)
      if (p2.phase[n] == phase) cut.insert({p2.position[2 * n], p2.position[2 * n + 1]});
    EXPECT_GT(slice.size(), 100u);
    EXPECT_EQ(slice, cut) << (phase == Phase::soil ? "soil" : "water") << ": " << slice.size() << " in the slice, "
                          << cut.size() << " in the section";
  }
}

// A bent section: each column centre lies on the polyline at its distance along it.
TEST(TerrainBuilder, BentSectionFollowsThePolyline) {
  Scratch scratch;
  const double dp = 0.5;
  const std::string section = "section: [{x: 836070, y: 818010}, {x: 836070, y: 818040}, {x: 836110, y: 818070}]";
  const auto spec = load_case_file(scratch.write("bent.yaml", hillside_case(2, dp, files() + section, 80.0)));
  const v1::TerrainGrid& g = spec.terrain().grid();
  ASSERT_EQ(g.nx(), 160);  // 30 m + 50 m
  for (int i : {0, 59, 60, 61, 159}) {
    const double s = (i + 0.5) * dp;
    const double x = s <= 30.0 ? 836070.0 : 836070.0 + 0.8 * (s - 30.0), y = s <= 30.0 ? 818010.0 + s : 818040.0 + 0.6 * (s - 30.0);
    EXPECT_NEAR(g.surface(i), hs::surface(x, y), kInterpolation) << "column " << i;
  }
  EXPECT_EQ(g.origin(0), 836070.0);
  EXPECT_EQ(g.origin(1), 818010.0);
}

// The lake fills the terrain up to its level: its highest particles sit dp/2 below the level
// (within a lattice spacing) wherever the ground is lower, and no water lies above the level.
TEST(TerrainBuilder, LakeFillsUpToItsLevel) {
  Scratch scratch;
  const double dp = 0.25;
  const std::string section = "section: [{x: 836000, y: 818040}, {x: 836120, y: 818040}]";
  const ParticleSet set =
      build_particle_set(load_case_file(scratch.write("lake.yaml", hillside_case(2, dp, files() + section, 120.0))));
  const auto water = columns(set.particles, Phase::water, dp);
  const auto soil = columns(set.particles, Phase::soil, dp);
  int wet = 0;
  for (const auto& [key, s] : soil) {
    const bool below_level = s.top + 0.5 * dp + kInterpolation < 102.0 - dp;
    if (!below_level) continue;
    ++wet;
    ASSERT_TRUE(water.count(key)) << "no water over column " << key.first;
    const Column& w = water.at(key);
    EXPECT_LE(w.top, 102.0);
    EXPECT_GT(w.top, 102.0 - dp);
    EXPECT_NEAR(w.bottom - s.top, dp, 1e-9) << "water rests on the soil in column " << key.first;
  }
  EXPECT_GT(wet, 100);
}

// A spec that carries the grid builds what the case file builds; a case text that names rasters
// is refused, as the server refuses it.
TEST(TerrainSpec, TheGridTravelsInTheSpecAndFilesDoNot) {
  Scratch scratch;
  const std::string section = "section: [{x: 836000, y: 818040}, {x: 836120, y: 818040}]";
  const std::string text = hillside_case(2, 0.5, files() + section, 120.0);
  const auto spec = load_case_file(scratch.write("case.yaml", text));
  EXPECT_TRUE(spec.terrain().surface_file().empty());
  EXPECT_EQ(spec.terrain().section_size(), 0);
  EXPECT_EQ(spec.terrain().grid().section_size(), 2);
  EXPECT_EQ(spec.terrain().grid().surface_source(), kSurface);
  validate_spec(spec);  // what CreateSimulation does with a spec
  EXPECT_EQ(build_particles(spec).position, build_particle_set(load_case_file(scratch.path("case.yaml"))).particles.position);
  try {
    load_case_text(text);
    FAIL() << "a case text naming rasters was accepted";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), "terrain.surface_file");
    EXPECT_NE(std::string(e.what()).find("only the loader of a case file reads"), std::string::npos) << e.what();
  }
  v1::ScenarioSpec bad = spec;
  bad.mutable_terrain()->mutable_grid()->set_base(3, bad.terrain().grid().surface(3) + 1.0);
  EXPECT_THROW(validate_spec(bad), CaseError);
}

// The shipped hillside cases build: soil in every column of the footprint, the saturated lake
// bed below the lake's level, the lake's water over it, dummies under all of it.
TEST(TerrainCases, ShippedHillsideCasesBuild) {
  for (const std::string name : {"hillside_dem_2d", "hillside_dem_3d"}) {
    SCOPED_TRACE(name);
    const auto spec = load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/" + name + ".yaml");
    const ParticleSet set = build_particle_set(spec);
    const v1::TerrainGrid& g = spec.terrain().grid();
    std::map<std::string, const BodyReport*> body;
    for (const BodyReport& b : set.bodies) body[b.name] = &b;
    // Soil in every column but those of the 3D case's house (hillside.h), founded into the bedrock.
    std::size_t house_columns = 0;
    const auto in_house = [&](double x, double y) {  // local x, y; the house's plan is two rectangles
      const double u = x + g.origin(0) - hs::kX0, v = y + g.origin(1) - hs::kY0;
      return u > 58 && v > 34 && ((u < 66 && v < 40) || (u < 62 && v < 46));
    };
    if (spec.dimensions() == 3) {
      ASSERT_GT(body.at("house")->count, 0u);
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) house_columns += in_house((i + 0.5) * spec.dp(), (j + 0.5) * spec.dp());
      ASSERT_EQ(house_columns, 16u * 12u + 8u * 12u);
      for (std::size_t n = 0; n < set.particles.phase.size(); ++n)
        if (set.particles.phase[n] != Phase::boundary)
          ASSERT_FALSE(in_house(set.particles.position[3 * n], set.particles.position[3 * n + 1]) &&
                       set.particles.position[3 * n + 2] < hs::kHouseRoof);
    }
    EXPECT_EQ(columns(set.particles, Phase::soil, spec.dp()).size(),
              std::size_t(g.nx()) * std::size_t(g.ny()) - house_columns);
    for (const char* b : {"bedrock", "lake_bed", "colluvium", "lake"}) ASSERT_GT(body.at(b)->count, 0u) << b;
    const int d = spec.dimensions();
    const BodyReport& bed = *body.at("lake_bed");
    for (std::size_t n = bed.first; n < bed.first + bed.count; ++n) EXPECT_LT(set.particles.position[n * d + d - 1], 102.0);
    const BodyReport& lake = *body.at("lake");
    for (std::size_t n = lake.first; n < lake.first + lake.count; ++n) EXPECT_LT(set.particles.position[n * d + d - 1], 102.0);
  }
}

struct BadTerrain {
  std::string name, terrain, key, message;
};

// Each bad input: the case error names the key (at its line) and the file.
TEST(TerrainErrors, EveryBadInputNamesItsKeyAndFile) {
  Scratch scratch;
  // A raster with a nodata hole at map (836050.5, 818040.5), and one in another CRS (UTM 50N).
  std::vector<double> values;
  for (int r = 0; r < 80; ++r)
    for (int c = 0; c < 160; ++c) values.push_back(hs::surface(hs::kX0 + c + 0.5, hs::kY0 + 80 - r - 0.5));
  std::vector<double> holed = values;
  holed[39 * 160 + 50] = -9999.0;
  write_geotiff(scratch.path("holed.tif"), 160, 80, hs::kX0, hs::kY0 + 80, 1.0, holed, hs::kEpsg, -9999.0);
  std::vector<double> base = values;
  for (double& z : base) z -= 2.0;
  write_geotiff(scratch.path("utm.tif"), 160, 80, hs::kX0, hs::kY0 + 80, 1.0, base, 32650);
  const std::string not_raster = scratch.write("notes.tif", "these are not pixels\n");
  const std::string w = window(hs::kX0 + 40, hs::kY0 + 30, hs::kX0 + 60, hs::kY0 + 50);
  const std::vector<BadTerrain> bad = {
      {"missing file", files(scratch.path("nothing.tif")) + w, "terrain.surface_file", "no such file: " + scratch.path("nothing.tif")},
      {"not a raster", files(not_raster) + w, "terrain.surface_file", not_raster + " is not a raster GDAL can read"},
      {"no overlap", files() + window(hs::kX0 + 500, hs::kY0, hs::kX0 + 520, hs::kY0 + 20), "terrain.window",
       "does not overlap " + kSurface},
      {"beyond the raster", files() + window(hs::kX0 + 150, hs::kY0 + 30, hs::kX0 + 170, hs::kY0 + 50), "terrain.window",
       "reaches beyond " + kSurface},
      {"nodata hole", files(scratch.path("holed.tif")) + window(hs::kX0 + 40, hs::kY0 + 30, hs::kX0 + 60, hs::kY0 + 50),
       "terrain.surface_file", "has no data (nodata) at map point"},
      {"base above surface", files(kBedrock, "base_file: " + kSurface) + w, "terrain.base_file",
       "puts the soil's base above the surface"},
      {"negative thickness", files(kSurface, "thickness: -1") + w, "terrain.thickness", "must be a positive number"},
      {"two bases", files(kSurface, "base_file: " + kBedrock + ", thickness: 2") + w, "terrain", "exactly one of"},
      {"other CRS", files(kSurface, "base_file: " + scratch.path("utm.tif")) + w, "terrain.base_file",
       "another coordinate reference system"},
      {"window too narrow", files() + window(hs::kX0 + 40, hs::kY0 + 30, hs::kX0 + 40.2, hs::kY0 + 50), "terrain.window",
       "narrower than dp"},
      {"section in 3D", files() + "section: [{x: 836010, y: 818010}, {x: 836020, y: 818010}]", "terrain.section",
       "is for 2D cases"},
  };
  for (const BadTerrain& b : bad) {
    const std::string path = scratch.write("bad.yaml", hillside_case(3, 0.5, b.terrain, 20.0, 20.0));
    try {
      load_case_file(path);
      ADD_FAILURE() << b.name << ": accepted";
    } catch (const CaseError& e) {
      EXPECT_EQ(e.key(), b.key) << b.name << ": " << e.what();
      EXPECT_EQ(e.line(), 5) << b.name << ": " << e.what();  // the terrain's line
      EXPECT_NE(std::string(e.what()).find(b.message), std::string::npos) << b.name << ": " << e.what();
    }
  }
}

TEST(TerrainErrors, LayersNeedTheirTerrainAndLevel) {
  const auto refused = [](const std::string& text, const std::string& key) {
    try {
      load_case_text(text);
      ADD_FAILURE() << key << ": accepted";
    } catch (const CaseError& e) {
      EXPECT_EQ(e.key(), key) << e.what();
    }
  };
  std::string text = hillside_case(2, 0.5, "", 20.0);
  text.replace(text.find("terrain: {}\n"), 12, "");
  refused(text, "bodies[0].shape.terrain");
  std::string no_level = text;
  no_level.replace(no_level.find(", level: 102"), 12, "");
  refused(no_level, "bodies[2].shape.terrain.level");
}

}  // namespace
}  // namespace cascade
