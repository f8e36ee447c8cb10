// The case's terrain (ScenarioSpec.terrain, scenario.proto): its rasters sampled at the centres of
// the lattice's columns (the case loader), the checks of a sampled grid (any spec), and the
// surfaces a terrain layer lies between (the geometry of a body of shape `terrain`).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/scenario/case_error.h"

namespace cascade {

// Throws the case's error for a key (the loader's carries the key's line in the case file); it
// must not return.
using TerrainFailure = std::function<void(const std::string& key, const std::string& message)>;

// Above this many columns (nx · ny) the loader refuses the terrain: 10⁷ columns, 80 MB per
// surface, is far beyond any case 5·10⁷ particles allow with a soil of a few layers.
constexpr double kMaxTerrainColumns = 1e7;

// Whether the terrain names rasters, a window or a section for the loader to read.
bool names_terrain_rasters(const cascade::v1::Terrain& terrain);

// Replaces the case file's raster names, window or section with `grid`: the surface and base
// elevations at the column centres (bilinear in the rasters), the local origin and the CRS.
// Relative file names are relative to `case_directory`. `dimensions` and `dp` are the case's.
// Fails (never returns) on a missing file, a file that is not a raster, a window or section that
// misses the raster or reaches beyond it, nodata at a column, a base above the surface, or rasters
// in different CRSs, naming the key and the file.
void expand_terrain(cascade::v1::Terrain& terrain, int dimensions, double dp, const std::filesystem::path& case_directory,
                    const TerrainFailure& fail);

// The checks of any spec's terrain: no file names left (the server reads no files that a request
// names), a grid whenever a body uses a terrain layer, its sizes, finite heights, base <= surface.
void check_terrain(const cascade::v1::ScenarioSpec& spec, const TerrainFailure& fail);

// A terrain layer's footprint and its two bounding surfaces, on the nodes of the grid extended by
// the footprint's edges (x: 0, dp/2, 3dp/2, ..., (nx − 1/2) dp, nx dp; the edge nodes repeat the
// outermost heights, so the surfaces stay constant beyond the outermost column centres).
struct LayerSurfaces {
  std::vector<double> x, y;       // extended node coordinates (2D: y = {0})
  std::vector<double> lower, upper;  // x.size() · y.size() heights, x fastest
};

// The surfaces of `layer` in the grid: GROUND base..surface, BEDROCK `bottom`..base, LAKE
// surface..max(level, surface).
LayerSurfaces layer_surfaces(const cascade::v1::TerrainLayer& layer, const cascade::v1::TerrainGrid& grid,
                             int dimensions, double dp, double bottom);

}  // namespace cascade
