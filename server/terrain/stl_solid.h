// Solid bodies from STL files (SolidMesh, scenario.proto): the loader reads the file named in a
// case (VTK's reader), places it and replaces it by the mesh; any spec's mesh is checked to be a
// closed, consistently oriented surface before the geometry (Shape::mesh) decomposes it.
#pragma once

#include <filesystem>
#include <string>

#include "cascade/v1/scenario.pb.h"
#include "server/terrain/terrain_grid.h"

namespace cascade {

// Above this many triangles a mesh is refused: the decomposition into columns (Shape::mesh) grows
// with the triangles' crossings in plan; decimate larger meshes (a wall, a dam or a building
// needs hundreds to a few thousand).
constexpr int kMaxMeshTriangles = 20000;
constexpr double kMaxMeshCoordinate = 1e8;  // m

// Whether any body shape or subtracted shape names an STL file.
bool names_stl_files(const cascade::v1::ScenarioSpec& spec);

// Reads every `mesh.stl_file` of the spec's bodies (relative to `case_directory`), applies scale,
// translate and map_coordinates (the terrain's grid must be expanded first), turns an inside-out
// mesh the right way out, and stores vertices and triangles in place of the file. Fails (never
// returns) naming the key and the file: missing file, not an STL file, an empty file, a mesh that is
// not closed or not consistently oriented.
void expand_stl_meshes(cascade::v1::ScenarioSpec& spec, const std::filesystem::path& case_directory,
                       const TerrainFailure& fail);

// What is wrong with a mesh's vertices and triangles, or "" when it bounds a solid: finite
// coordinates, indices in range, no triangle without area, every edge shared by exactly two
// triangles that run along it in opposite directions, and a positive enclosed volume (normals
// outward).
std::string mesh_defect(const cascade::v1::SolidMesh& mesh);

}  // namespace cascade
