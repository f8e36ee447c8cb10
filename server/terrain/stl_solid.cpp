#include "server/terrain/stl_solid.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <optional>

#include "server/scenario/number_text.h"

namespace cascade {
namespace pb = cascade::v1;
namespace {

// Calls `f(key, mesh)` for every mesh shape of the spec's bodies, with its key.
template <typename F>
void for_each_mesh(pb::ScenarioSpec& spec, F f) {
  for (int i = 0; i < spec.bodies_size(); ++i) {
    pb::Body& b = *spec.mutable_bodies(i);
    const std::string body = "bodies[" + std::to_string(i) + "]";
    if (b.shape().has_mesh()) f(body + ".shape.mesh", *b.mutable_shape()->mutable_mesh());
    for (int k = 0; k < b.subtract_size(); ++k)
      if (b.subtract(k).has_mesh()) f(body + ".subtract[" + std::to_string(k) + "].mesh", *b.mutable_subtract(k)->mutable_mesh());
  }
}

Eigen::Vector3d vertex(const pb::SolidMesh& m, std::uint32_t v) {
  return {m.vertices(3 * int(v)), m.vertices(3 * int(v) + 1), m.vertices(3 * int(v) + 2)};
}

std::string point_text(const pb::SolidMesh& m, std::uint32_t v) {
  const Eigen::Vector3d p = vertex(m, v);
  return "(" + number_text(p.x()) + ", " + number_text(p.y()) + ", " + number_text(p.z()) + ")";
}

// A binary STL is an 80-byte header, a triangle count and 50 bytes per triangle; VTK's reader
// takes any file that does not start with "solid" as binary and reads noise as triangles, so the
// size is checked first. Returns why the file is not an STL file, or nothing.
std::optional<std::string> not_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot be opened";
  char head[84] = {};
  in.read(head, sizeof head);
  const std::streamsize got = in.gcount();
  std::error_code error;
  const long long size = static_cast<long long>(std::filesystem::file_size(path, error));
  if (got >= 5 && std::string(head, 5) == "solid") return std::nullopt;  // ASCII (or a binary file whose header says so)
  if (got < 84) return "is not an STL file: " + std::to_string(size) + " bytes, too short for a binary STL's header";
  std::uint32_t count = 0;
  for (int b = 3; b >= 0; --b) count = (count << 8) | static_cast<unsigned char>(head[80 + b]);  // little-endian
  if (size != 84 + 50LL * count)
    return "is not an STL file: neither ASCII ('solid' ...) nor binary (its header counts " + std::to_string(count) +
           " triangles, " + std::to_string(84 + 50LL * count) + " bytes, but the file has " + std::to_string(size) + ")";
  return std::nullopt;
}

// The file's triangles with shared vertices merged (VTK's reader, exact coordinates), or the
// reader's error.
pb::SolidMesh read_stl(const std::string& path, const std::string& key, const TerrainFailure& fail) {
  if (!std::filesystem::is_regular_file(path)) fail(key + ".stl_file", path + ": no such file");
  if (const auto why = not_stl(path)) fail(key + ".stl_file", path + " " + *why);
  auto reader = vtkSmartPointer<vtkSTLReader>::New();
  std::string error;
  auto observer = vtkSmartPointer<vtkCallbackCommand>::New();  // keeps VTK's messages off stderr
  observer->SetClientData(&error);
  observer->SetCallback([](vtkObject*, unsigned long event, void* client, void* text) {
    auto* first = static_cast<std::string*>(client);
    if (event == vtkCommand::ErrorEvent && first->empty() && text) *first = static_cast<const char*>(text);
  });
  reader->AddObserver(vtkCommand::ErrorEvent, observer);
  reader->AddObserver(vtkCommand::WarningEvent, observer);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  reader->SetFileName(path.c_str());
  reader->MergingOn();
  reader->Update();
  if (!error.empty()) {
    const auto colon = error.find("): ");  // VTK's text: "ERROR: In file, line N\nvtkSTLReader (0x..): message"
    fail(key + ".stl_file", path + " is not a readable STL file: " +
                                (colon == std::string::npos ? error : error.substr(colon + 3)));
  }
  vtkPolyData* data = reader->GetOutput();
  if (data->GetNumberOfPolys() == 0) fail(key + ".stl_file", path + " holds no triangles");
  if (data->GetNumberOfPolys() > kMaxMeshTriangles)
    fail(key + ".stl_file", path + " has " + std::to_string(data->GetNumberOfPolys()) + " triangles, more than the limit of " +
                                std::to_string(kMaxMeshTriangles) + ": decimate it (e.g. ParaView's Decimate filter)");
  pb::SolidMesh mesh;
  for (vtkIdType p = 0; p < data->GetNumberOfPoints(); ++p) {
    double x[3];
    data->GetPoint(p, x);
    for (double c : x) mesh.add_vertices(c);
  }
  vtkCellArray* polys = data->GetPolys();
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);) {
    if (n != 3) fail(key + ".stl_file", path + " has a facet of " + std::to_string(n) + " vertices; STL facets are triangles");
    for (int k = 0; k < 3; ++k) mesh.add_triangles(static_cast<std::uint32_t>(ids[k]));
  }
  return mesh;
}

// |(b − a) × (c − a)|², zero for a triangle whose vertices are on a line.
double triangle_area2(const pb::SolidMesh& m, const std::uint32_t v[3]) {
  const Eigen::Vector3d a = vertex(m, v[0]);
  return (vertex(m, v[1]) - a).cross(vertex(m, v[2]) - a).squaredNorm();
}

double signed_volume(const pb::SolidMesh& m) {
  double six_v = 0.0;  // Σ a · (b × c) over the triangles, six times the enclosed volume
  for (int t = 0; t + 2 < m.triangles_size(); t += 3)
    six_v += vertex(m, m.triangles(t)).dot(vertex(m, m.triangles(t + 1)).cross(vertex(m, m.triangles(t + 2))));
  return six_v / 6.0;
}

}  // namespace

bool names_stl_files(const pb::ScenarioSpec& spec) {
  for (const pb::Body& b : spec.bodies()) {
    if (b.shape().has_mesh() && !b.shape().mesh().stl_file().empty()) return true;
    for (const pb::Shape& s : b.subtract())
      if (s.has_mesh() && !s.mesh().stl_file().empty()) return true;
  }
  return false;
}

std::string mesh_defect(const pb::SolidMesh& m) {
  if (m.vertices_size() % 3 != 0) return "vertices need 3 coordinates each (has " + std::to_string(m.vertices_size()) + ")";
  for (double c : m.vertices())  // beyond 10⁸ m (far off the Earth) the triangles' normals lose their meaning
    if (!(std::abs(c) <= kMaxMeshCoordinate)) return "vertex coordinates must be finite numbers within ±1e8 m";
  if (m.triangles_size() % 3 != 0 || m.triangles_size() < 12)
    return "needs 3 vertex indices per triangle and at least 4 triangles (has " + std::to_string(m.triangles_size()) +
           " indices)";
  if (m.triangles_size() / 3 > kMaxMeshTriangles)
    return "has " + std::to_string(m.triangles_size() / 3) + " triangles, more than the limit of " +
           std::to_string(kMaxMeshTriangles);
  const std::uint32_t nv = static_cast<std::uint32_t>(m.vertices_size() / 3);
  // Each undirected edge (low, high) → the triangles running along it low → high and high → low.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::array<int, 2>> edges;
  for (int t = 0; t < m.triangles_size() / 3; ++t) {
    std::uint32_t v[3];
    for (int k = 0; k < 3; ++k) {
      v[k] = m.triangles(3 * t + k);
      if (v[k] >= nv) return "triangle " + std::to_string(t) + " names vertex " + std::to_string(v[k]) + " of " + std::to_string(nv);
    }
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0] || triangle_area2(m, v) == 0.0)
      return "triangle " + std::to_string(t) + " at " + point_text(m, v[0]) + " has no area (its vertices are on a line)";
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}][a < b ? 0 : 1] += 1;
    }
  }
  for (const auto& [edge, runs] : edges) {
    const std::string where = "the edge from " + point_text(m, edge.first) + " to " + point_text(m, edge.second);
    const int n = runs[0] + runs[1];
    if (n == 1) return where + " borders one triangle only: the surface has a hole there (the mesh is not closed)";
    if (n > 2) return where + " borders " + std::to_string(n) + " triangles: the surface is not a manifold (bodies touching along an edge)";
    if (runs[0] != 1)
      return where + " is run the same way by both its triangles: their orientations disagree (one faces in, one out)";
  }
  if (!(signed_volume(m) > 0.0)) return "encloses no volume with its triangles counter-clockwise seen from outside";
  return "";
}

void expand_stl_meshes(pb::ScenarioSpec& spec, const std::filesystem::path& case_directory, const TerrainFailure& fail) {
  for_each_mesh(spec, [&](const std::string& key, pb::SolidMesh& m) {
    if (m.vertices_size() > 0 || m.triangles_size() > 0)
      fail(key + ".vertices", "are set by the loader from stl_file: leave vertices and triangles out of a case file");
    if (m.stl_file().empty()) fail(key + ".stl_file", "is missing: the STL file of the solid");
    if (spec.dimensions() != 3) fail(key, "is a 3D shape (a solid from an STL file); a 2D case uses polygon");
    const std::string path = (case_directory / m.stl_file()).lexically_normal().string();
    pb::SolidMesh read = read_stl(path, key, fail);
    if (signed_volume(read) < 0.0) {  // an inside-out file (normals inward): the same solid, its triangles reversed
      for (int t = 0; t + 2 < read.triangles_size(); t += 3) {
        const std::uint32_t v = read.triangles(t + 1);
        read.set_triangles(t + 1, read.triangles(t + 2));
        read.set_triangles(t + 2, v);
      }
    }
    if (const std::string defect = mesh_defect(read); !defect.empty()) fail(key + ".stl_file", path + ": " + defect);

    const double scale = m.scale() == 0.0 ? 1.0 : m.scale();
    if (!(scale > 0.0) || !std::isfinite(scale)) fail(key + ".scale", "must be a positive number (is " + number_text(m.scale()) + ")");
    std::array<double, 3> shift{0.0, 0.0, 0.0};
    if (m.translate_size() != 0 && m.translate_size() != 3) fail(key + ".translate", "needs [x, y, z] or nothing");
    for (int c = 0; c < m.translate_size(); ++c) {
      if (!std::isfinite(m.translate(c))) fail(key + ".translate", "components must be finite numbers");
      shift[c] = m.translate(c);
    }
    if (m.map_coordinates()) {
      const pb::TerrainGrid& g = spec.terrain().grid();
      if (g.origin_size() != 2)
        fail(key + ".map_coordinates", "needs the case's terrain (terrain.surface_file and its window): its origin is "
                                       "what map coordinates are shifted by");
      shift[0] -= g.origin(0), shift[1] -= g.origin(1);
    }
    m.clear_vertices();
    for (int k = 0; k < read.vertices_size(); ++k) m.add_vertices(scale * read.vertices(k) + shift[k % 3]);
    *m.mutable_triangles() = read.triangles();
    m.set_source(path);
    m.clear_stl_file();
    m.clear_scale();
    m.clear_translate();
    m.clear_map_coordinates();
  });
}

}  // namespace cascade
