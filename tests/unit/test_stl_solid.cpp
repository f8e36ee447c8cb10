// Solid bodies from STL files (docs/cases.md, "Solids from STL files"): a closed STL box gives the
// same particles, boundary particles and ghost nodes as the same box built from the case's own
// shape; a non-convex mesh (a C-shaped block with a slot, a trapezoidal dam) the same as its
// extruded polygon; scale, translate and map coordinates place it; every bad input gets its error
// naming the key and the file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/scenario/case_error.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/case_validation.h"
#include "server/scenario/geometry.h"
#include "server/scenario/particle_builder.h"
#include "tests/unit/scratch_folder.h"

namespace cascade {
namespace {

namespace fs = std::filesystem;

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

// The closed surface of an (x, z) outline, counter-clockwise in (x, z), extruded from y0 to y1: the
// caps as the given triangles of outline indices (counter-clockwise in (x, z)) and two triangles
// per side. For u, v in the (x, z) plane, (u × v)_y = −(u_x v_z − u_z v_x): a cap triangle
// counter-clockwise in (x, z) faces −y, out of the y0 cap; the y1 cap takes it reversed. A side on
// the outline's edge (dx, dz) faces (dz, 0, −dx), outwards.
Mesh extruded(const std::vector<std::array<double, 2>>& outline, const std::vector<std::array<int, 3>>& caps,
              double y0, double y1) {
  Mesh m;
  const int n = int(outline.size());
  for (double y : {y0, y1})
    for (const auto& p : outline) m.vertices.emplace_back(p[0], y, p[1]);
  for (const auto& t : caps) {
    m.triangles.push_back({t[0], t[1], t[2]});
    m.triangles.push_back({n + t[0], n + t[2], n + t[1]});
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.push_back({i, n + i, n + j});
    m.triangles.push_back({i, n + j, j});
  }
  return m;
}

Mesh box_mesh(const Vec3& lo, const Vec3& hi) {
  return extruded({{lo.x(), lo.z()}, {hi.x(), lo.z()}, {hi.x(), hi.z()}, {lo.x(), hi.z()}}, {{0, 1, 2}, {0, 2, 3}},
                  lo.y(), hi.y());
}

std::string ascii_stl(const Mesh& m) {
  std::ostringstream s;
  s.precision(17);
  s << "solid test\n";
  for (const auto& t : m.triangles) {
    const Vec3 n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).normalized();
    s << " facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n  outer loop\n";
    for (int v : t) s << "   vertex " << m.vertices[v].x() << " " << m.vertices[v].y() << " " << m.vertices[v].z() << "\n";
    s << "  endloop\n endfacet\n";
  }
  s << "endsolid test\n";
  return s.str();
}

// Binary STL: 80-byte header, uint32 count, then per triangle 12 float32 and a uint16 (little-endian
// on this machine, as the format is). Coordinates must be exact in float32.
std::string binary_stl(const Mesh& m) {
  std::string out(80, ' ');
  const auto put = [&](const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); };
  const std::uint32_t count = std::uint32_t(m.triangles.size());
  put(&count, 4);
  for (const auto& t : m.triangles) {
    float f[12] = {};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) f[3 + 3 * k + c] = float(m.vertices[t[k]][c]);
    put(f, sizeof f);
    const std::uint16_t attribute = 0;
    put(&attribute, 2);
  }
  return out;
}

// A scratch folder for this file's cases and inputs.
class Scratch : public testing::ScratchFolder {
 public:
  Scratch() : ScratchFolder("cascade_stl") {}
};

// Water 0.3 m deep in a 1 m × 1 m tank (floor and four walls) around a solid `obstacle` (the YAML
// of a shape) standing on the floor: its dummies, the floor's wetted surface cut by its footprint,
// and the water cut by its volume all depend on the obstacle's geometry.
std::string tank_case(const std::string& obstacle, double dp = 0.05) {
  std::ostringstream c;
  c << "name: stl_tank\ndimensions: 3\ndp: " << dp << "\nend_time: 1\n"
    << "domain: {min: [-0.2, -0.2, -0.2], max: [1.2, 1.2, 0.8]}\ngravity: [0, 0, -9.81]\n"
    << "materials:\n  - {name: water, water: {density: 1000}}\n"
    << "bodies:\n"
    << "  - name: tank\n    kind: boundary\n    shape: {box: {min: [-0.2, -0.2, -0.2], max: [1.2, 1.2, 0.6]}}\n"
    << "    subtract: [{box: {min: [0, 0, 0], max: [1, 1, 0.8]}}]\n"
    << "  - name: obstacle\n    kind: boundary\n    shape: " << obstacle << "\n"
    << "  - name: water\n    kind: fluid\n    material: water\n    shape: {box: {min: [0, 0, 0], max: [1, 1, 0.3]}}\n";
  return c.str();
}

void expect_same_particles(const ParticleSet& a, const ParticleSet& b, double ghost_tolerance) {
  ASSERT_EQ(a.particles.phase.size(), b.particles.phase.size());
  EXPECT_EQ(a.particles.phase, b.particles.phase);
  EXPECT_EQ(a.particles.position, b.particles.position);
  EXPECT_EQ(a.particles.body, b.particles.body);
  ASSERT_EQ(a.particles.ghost.size(), b.particles.ghost.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < a.particles.ghost.size(); ++k)
    worst = std::max(worst, std::abs(a.particles.ghost[k] - b.particles.ghost[k]));
  EXPECT_LE(worst, ghost_tolerance);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    EXPECT_EQ(a.bodies[k].count, b.bodies[k].count) << a.bodies[k].name;
    EXPECT_NEAR(a.bodies[k].wetted_surface, b.bodies[k].wetted_surface, 1e-9) << a.bodies[k].name;
  }
}

// Off the lattice, into the floor, and exact in float32: STL stores float32 coordinates (VTK's
// reader reads ASCII files into float32 too), so a mesh and a case shape agree to the bit only on
// such numbers (binary fractions here).
const Vec3 kLo(0.328125, 0.265625, -0.1875), kHi(0.7109375, 0.640625, 0.453125);

TEST(StlSolid, ClosedStlBoxGivesTheSameParticlesAsTheBox) {
  Scratch scratch;
  const std::string box = "{box: {min: [0.328125, 0.265625, -0.1875], max: [0.7109375, 0.640625, 0.453125]}}";
  const ParticleSet reference = build_particle_set(load_case_file(scratch.write("box.yaml", tank_case(box))));
  ASSERT_GT(reference.bodies[1].count, 300u);
  ASSERT_GT(reference.bodies[1].wetted_surface, 0.5);
  const Mesh mesh = box_mesh(kLo, kHi);
  scratch.write("box_ascii.stl", ascii_stl(mesh));
  const ParticleSet ascii = build_particle_set(
      load_case_file(scratch.write("ascii.yaml", tank_case("{mesh: {stl_file: box_ascii.stl}}"))));
  expect_same_particles(reference, ascii, 1e-12);
  // Binary, in millimetres about the box's corner (whole millimetres, exact in float32): scale
  // and translate put it back, up to the rounding of 0.328125 + 0.001 · 382.8125.
  Mesh mm = box_mesh(Vec3::Zero(), 1000.0 * (kHi - kLo));
  scratch.write("box_mm.stl", binary_stl(mm));
  const ParticleSet binary = build_particle_set(load_case_file(scratch.write(
      "binary.yaml", tank_case("{mesh: {stl_file: box_mm.stl, scale: 0.001, translate: [0.328125, 0.265625, -0.1875]}}"))));
  expect_same_particles(reference, binary, 1e-9);
}

// An outline's YAML as an extruded_polygon, the reference for its mesh.
std::string extruded_polygon_yaml(const std::vector<std::array<double, 2>>& outline, double y0, double y1) {
  std::ostringstream s;
  s.precision(17);
  s << "{extruded_polygon: {vertices: [";
  for (std::size_t k = 0; k < outline.size(); ++k) s << (k ? ", " : "") << "{x: " << outline[k][0] << ", z: " << outline[k][1] << "}";
  s << "], y_min: " << y0 << ", y_max: " << y1 << "}}";
  return s.str();
}

// A block with a slot open towards +x below the water's surface (a column through the slot holds
// two stretches of solid), and a trapezoidal dam with sloping faces: each as its extruded polygon
// and as an STL mesh.
TEST(StlSolid, NonConvexMeshesGiveTheSameParticlesAsTheirExtrudedPolygons) {
  struct Solid {
    const char* name;
    std::vector<std::array<double, 2>> outline;
    std::vector<std::array<int, 3>> caps;
  };
  const std::vector<Solid> solids = {
      {"slotted block",
       {{0.3125, -0.1875}, {0.734375, -0.1875}, {0.734375, 0.1171875}, {0.515625, 0.1171875}, {0.515625, 0.3125}, {0.734375, 0.3125}, {0.734375, 0.5234375}, {0.3125, 0.5234375}},
       {{0, 1, 2}, {0, 2, 3}, {0, 3, 7}, {7, 3, 4}, {7, 4, 5}, {7, 5, 6}}},
      {"dam", {{0.203125, -0.1875}, {0.796875, -0.1875}, {0.59375, 0.4453125}, {0.40625, 0.4453125}}, {{0, 1, 2}, {0, 2, 3}}},
  };
  for (const Solid& solid : solids) {
    SCOPED_TRACE(solid.name);
    Scratch scratch;
    const ParticleSet reference = build_particle_set(
        load_case_file(scratch.write("polygon.yaml", tank_case(extruded_polygon_yaml(solid.outline, 0.28125, 0.65625)))));
    ASSERT_GT(reference.bodies[1].count, 300u);
    scratch.write("solid.stl", ascii_stl(extruded(solid.outline, solid.caps, 0.28125, 0.65625)));
    const ParticleSet mesh =
        build_particle_set(load_case_file(scratch.write("mesh.yaml", tank_case("{mesh: {stl_file: solid.stl}}"))));
    expect_same_particles(reference, mesh, 1e-9);
  }
}

// Points on a lattice finer than the shapes' features, against the extruded polygon's own test.
TEST(StlSolid, ContainsAgreesWithTheExtrudedPolygon) {
  const std::vector<std::array<double, 2>> outline = {{0.3125, -0.1875}, {0.734375, -0.1875}, {0.734375, 0.1171875}, {0.515625, 0.1171875}, {0.515625, 0.3125}, {0.734375, 0.3125}, {0.734375, 0.5234375}, {0.3125, 0.5234375}};
  const Mesh m = extruded(outline, {{0, 1, 2}, {0, 2, 3}, {0, 3, 7}, {7, 3, 4}, {7, 4, 5}, {7, 5, 6}}, 0.28125, 0.65625);
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (const auto& t : m.triangles) triangles.push_back({std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});
  const Shape mesh = Shape::mesh(m.vertices, triangles, "mesh");
  std::vector<Eigen::Vector2d> polygon;
  for (const auto& p : outline) polygon.emplace_back(p[0], p[1]);
  const Shape reference = Shape::extruded_polygon(polygon, 0.28125, 0.65625, "polygon");
  int inside = 0, checked = 0;
  for (double x = 0.2013; x < 0.85; x += 0.0107)
    for (double y = 0.2017; y < 0.75; y += 0.0131)
      for (double z = -0.3011; z < 0.6; z += 0.0093) {
        const Vec3 p(x, y, z);
        ASSERT_EQ(mesh.contains(p), reference.contains(p)) << x << " " << y << " " << z;
        inside += reference.contains(p), ++checked;
      }
  EXPECT_GT(inside, checked / 10);
  EXPECT_LT(inside, checked / 2);
}

// A retaining wall given in the terrain's map coordinates (EPSG:2326, as the hillside rasters)
// lands where the same wall in local coordinates does (float32 holds map X near 836000 m to
// 1/16 m: the wall's coordinates are multiples of it).
TEST(StlSolid, MapCoordinatesAreShiftedByTheTerrainsOrigin) {
  Scratch scratch;
  const std::string terrain = std::string(CASCADE_SOURCE_DIR) + "/cases/terrain/";
  const auto case_text = [&](const std::string& wall) {
    return "name: wall\ndimensions: 3\ndp: 0.5\nend_time: 1\n"
           "terrain: {surface_file: " + terrain + "hillside_surface.tif, base_file: " + terrain +
           "hillside_bedrock.tif, window: {min: [836000, 818030], max: [836030, 818040]}}\n"
           "domain: {min: [0, 0, 96], max: [30, 10, 130]}\ngravity: [0, 0, -9.81]\n"
           "materials:\n  - {name: water, water: {density: 1000}}\n"
           "bodies:\n  - {name: rock, kind: boundary, shape: {terrain: {layer: bedrock}}}\n"
           "  - {name: wall, kind: boundary, shape: " + wall + "}\n"
           "  - {name: lake, kind: fluid, material: water, shape: {terrain: {layer: lake, level: 102}}}\n";
  };
  const ParticleSet local = build_particle_set(load_case_file(
      scratch.write("local.yaml", case_text("{box: {min: [16.25, 0, 96], max: [17.3125, 10, 103]}}"))));
  ASSERT_GT(local.bodies[1].count, 100u);
  scratch.write("wall_map.stl", ascii_stl(box_mesh(Vec3(836016.25, 818030, 96), Vec3(836017.3125, 818040, 103))));
  const ParticleSet map = build_particle_set(load_case_file(
      scratch.write("map.yaml", case_text("{mesh: {stl_file: wall_map.stl, map_coordinates: true}}"))));
  expect_same_particles(local, map, 1e-6);
}

// Each bad input: the error names the key (with its line) and the file.
TEST(StlSolid, EveryBadInputNamesItsKeyAndFile) {
  Scratch scratch;
  Mesh open = box_mesh(kLo, kHi);
  open.triangles.pop_back();
  Mesh flipped_one = box_mesh(kLo, kHi);
  std::swap(flipped_one.triangles[3][1], flipped_one.triangles[3][2]);
  Mesh overlapping = box_mesh(kLo, kHi);  // two boxes that overlap, as one closed mesh
  const Mesh second = box_mesh(kLo + Vec3(0.1, 0.1, 0.1), kHi + Vec3(0.1, 0.1, 0.1));
  for (const auto& t : second.triangles) overlapping.triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
  overlapping.vertices.insert(overlapping.vertices.end(), second.vertices.begin(), second.vertices.end());
  scratch.write("open.stl", ascii_stl(open));
  scratch.write("flipped_one.stl", ascii_stl(flipped_one));
  scratch.write("overlapping.stl", ascii_stl(overlapping));
  scratch.write("hello.stl", "hello world\n");
  scratch.write("short.stl", std::string(100, 'x'));
  scratch.write("garbled.stl", "solid broken\n facet normal 0 0 1\n  outer loop\n   vertex 0 0\n");
  scratch.write("empty_solid.stl", "solid nothing\nendsolid nothing\n");
  scratch.write("box.stl", ascii_stl(box_mesh(kLo, kHi)));
  struct Bad {
    std::string shape, key, message;
  };
  const std::vector<Bad> bad = {
      {"{mesh: {stl_file: missing.stl}}", "bodies[1].shape.mesh.stl_file", "missing.stl: no such file"},
      {"{mesh: {stl_file: hello.stl}}", "bodies[1].shape.mesh.stl_file", "hello.stl is not an STL file"},
      {"{mesh: {stl_file: garbled.stl}}", "bodies[1].shape.mesh.stl_file", "garbled.stl is not a readable STL file"},
      {"{mesh: {stl_file: short.stl}}", "bodies[1].shape.mesh.stl_file", "short.stl is not an STL file"},
      {"{mesh: {stl_file: empty_solid.stl}}", "bodies[1].shape.mesh.stl_file", "empty_solid.stl holds no triangles"},
      {"{mesh: {stl_file: open.stl}}", "bodies[1].shape.mesh.stl_file", "the mesh is not closed"},
      {"{mesh: {stl_file: flipped_one.stl}}", "bodies[1].shape.mesh.stl_file", "orientations disagree"},
      {"{mesh: {stl_file: overlapping.stl}}", "bodies[1].shape.mesh", "crosses itself"},
      {"{mesh: {}}", "bodies[1].shape.mesh.stl_file", "is missing"},
      {"{mesh: {stl_file: box.stl, vertices: [0, 0, 0]}}", "bodies[1].shape.mesh.vertices", "set by the loader"},
      {"{mesh: {stl_file: box.stl, scale: -2}}", "bodies[1].shape.mesh.scale", "positive"},
      {"{mesh: {stl_file: box.stl, translate: [1, 2]}}", "bodies[1].shape.mesh.translate", "[x, y, z]"},
      {"{mesh: {stl_file: box.stl, map_coordinates: true}}", "bodies[1].shape.mesh.map_coordinates", "terrain"},
  };
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.shape);
    const std::string path = scratch.write("bad.yaml", tank_case(b.shape));
    try {
      build_particle_set(load_case_file(path));
      ADD_FAILURE() << "no error";
    } catch (const CaseError& e) {
      EXPECT_EQ(e.key(), b.key) << e.what();
      EXPECT_GT(e.line(), 0) << e.what();
      EXPECT_NE(std::string(e.what()).find(b.message), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    }
  }
}

// A 2D case has no STL solids; a case sent as text, or a spec, carries the mesh, never a file name;
// a spec's mesh is checked as the file's is.
TEST(StlSolid, SpecsCarryTheMeshAndTheMeshIsChecked) {
  Scratch scratch;
  scratch.write("box.stl", ascii_stl(box_mesh(kLo, kHi)));
  const v1::ScenarioSpec spec = load_case_file(scratch.write("box.yaml", tank_case("{mesh: {stl_file: box.stl}}")));
  const v1::SolidMesh& m = spec.bodies(1).shape().mesh();
  EXPECT_TRUE(m.stl_file().empty());
  EXPECT_EQ(m.vertices_size(), 8 * 3);
  EXPECT_EQ(m.triangles_size(), 12 * 3);
  EXPECT_NE(m.source().find("box.stl"), std::string::npos);
  const auto error_of = [](const std::function<void()>& f) -> std::string {
    try {
      f();
    } catch (const CaseError& e) {
      return e.key() + ": " + e.what();
    }
    return "";
  };
  const auto spec_error = [&](const v1::ScenarioSpec& s) {
    return error_of([&] { check_spec(s, [](const std::string& k, const std::string& msg) { throw CaseError(k, msg); }); });
  };
  EXPECT_NE(error_of([&] { load_case_text(tank_case("{mesh: {stl_file: box.stl}}")); }).find("bodies[1].shape.mesh.stl_file"),
            std::string::npos);
  // A case text may carry the mesh itself; its indices are whole numbers >= 0.
  EXPECT_NE(error_of([&] { load_case_text(tank_case("{mesh: {vertices: [0, 0, 0], triangles: [0, -1, 2]}}")); })
                .find("bodies[1].shape.mesh.triangles[1]': expected a whole number >= 0, got '-1'"),
            std::string::npos);
  v1::ScenarioSpec broken = spec;
  broken.mutable_bodies(1)->mutable_shape()->mutable_mesh()->set_triangles(5, 99);
  EXPECT_NE(spec_error(broken).find("names vertex 99"), std::string::npos);
  v1::ScenarioSpec inside_out = spec;
  for (int t = 0; t < 12; ++t) {
    auto* tri = inside_out.mutable_bodies(1)->mutable_shape()->mutable_mesh()->mutable_triangles();
    std::swap(*tri->Mutable(3 * t + 1), *tri->Mutable(3 * t + 2));
  }
  EXPECT_NE(spec_error(inside_out).find("encloses no volume"), std::string::npos);
  const std::string text2d = "name: flat\ndimensions: 2\ndp: 0.05\nend_time: 1\ndomain: {min: [0, 0], max: [1, 1]}\n"
                             "gravity: [0, -9.81]\nmaterials:\n  - {name: water, water: {density: 1000}}\nbodies:\n"
                             "  - {name: wall, kind: boundary, shape: {mesh: {stl_file: box.stl}}}\n"
                             "  - {name: water, kind: fluid, material: water, shape: {box: {min: [0, 0], max: [1, 0.5]}}}\n";
  EXPECT_NE(error_of([&] { load_case_file(scratch.write("flat.yaml", text2d)); }).find("is a 3D shape"), std::string::npos);
}

// A closed, consistently oriented box whose top corner over (1, 0) is pulled down through its
// floor: the top's triangle there crosses the floor's although, at the centres of the plan's
// pieces, it still lies above it.
TEST(StlSolid, SurfaceCrossingItselfInsideAColumnIsRefused) {
  std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, -0.5}, {1, 1, 1}, {0, 1, 1}};
  // Floor and top split along the same diagonal (0, 0)–(1, 1): two plan pieces.
  const std::vector<std::array<std::uint32_t, 3>> triangles = {
      {0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
      {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  try {
    Shape::mesh(v, triangles, "bodies[1].shape.mesh");
    ADD_FAILURE() << "no error";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), "bodies[1].shape.mesh");
    EXPECT_NE(e.message().find("crosses itself above map point (1, 0)"), std::string::npos) << e.what();
  }
  v[5].z() = 1.0;  // the box itself is fine
  EXPECT_EQ(Shape::mesh(v, triangles, "mesh").cells().size(), 2u);
}

// An STL file written inside out (every normal inward) is the same solid: the loader turns it.
TEST(StlSolid, InsideOutFileIsTurned) {
  Scratch scratch;
  Mesh inverted = box_mesh(kLo, kHi);
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  scratch.write("inverted.stl", ascii_stl(inverted));
  scratch.write("box.stl", ascii_stl(box_mesh(kLo, kHi)));
  expect_same_particles(build_particle_set(load_case_file(scratch.write("a.yaml", tank_case("{mesh: {stl_file: box.stl}}")))),
                        build_particle_set(load_case_file(scratch.write("b.yaml", tank_case("{mesh: {stl_file: inverted.stl}}")))),
                        0.0);
}

}  // namespace
}  // namespace cascade
