#include "server/terrain/terrain_grid.h"

#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "server/scenario/number_text.h"
#include "server/terrain/raster.h"

namespace cascade {
namespace pb = cascade::v1;
namespace {

struct MapPoint {
  double x, y;
};

std::string map_point_text(const MapPoint& p) { return "(" + number_text(p.x) + ", " + number_text(p.y) + ")"; }

std::string extent_text(const std::array<double, 4>& e) {
  return "X " + number_text(e[0]) + " to " + number_text(e[2]) + ", Y " + number_text(e[1]) + " to " + number_text(e[3]);
}

// The map points of the column centres, x fastest, and the grid's size.
struct Columns {
  int nx = 0, ny = 0;
  std::vector<MapPoint> points;
  MapPoint origin{0.0, 0.0};
  std::string key;  // terrain.window or terrain.section
};

int whole_spacings(double length, double dp) { return static_cast<int>(std::floor(length / dp + 1e-9)); }

void check_size(double nx, double ny, const TerrainFailure& fail) {
  if (nx * ny > kMaxTerrainColumns)
    fail("dp", "gives " + number_text(nx * ny) + " terrain columns, more than the limit of " +
                   number_text(kMaxTerrainColumns) + ": increase dp or shrink the window");
}

Columns window_columns(const pb::Terrain& t, double dp, const TerrainFailure& fail) {
  Columns c;
  c.key = "terrain.window";
  const pb::MapWindow& w = t.window();
  if (w.min_size() != 2 || w.max_size() != 2) fail(c.key, "needs min: [X, Y] and max: [X, Y] in map coordinates");
  for (int a = 0; a < 2; ++a)
    if (!std::isfinite(w.min(a)) || !std::isfinite(w.max(a))) fail(c.key, "coordinates must be finite numbers");
  const double nx = std::floor((w.max(0) - w.min(0)) / dp + 1e-9), ny = std::floor((w.max(1) - w.min(1)) / dp + 1e-9);
  if (nx < 1 || ny < 1) fail(c.key, "is narrower than dp = " + number_text(dp) + " m along X or Y");
  check_size(nx, ny, fail);
  c.nx = int(nx), c.ny = int(ny);
  c.origin = {w.min(0), w.min(1)};
  c.points.reserve(std::size_t(c.nx) * std::size_t(c.ny));
  for (int j = 0; j < c.ny; ++j)
    for (int i = 0; i < c.nx; ++i) c.points.push_back({c.origin.x + (i + 0.5) * dp, c.origin.y + (j + 0.5) * dp});
  return c;
}

Columns section_columns(const pb::Terrain& t, double dp, const TerrainFailure& fail) {
  Columns c;
  c.key = "terrain.section";
  if (t.section_size() < 2) fail(c.key, "needs at least 2 map points [{x: X, y: Y}, ...]");
  std::vector<double> start{0.0};  // the distance along the section to each point
  for (int k = 0; k + 1 < t.section_size(); ++k) {
    const pb::MapPoint &a = t.section(k), &b = t.section(k + 1);
    if (!std::isfinite(a.x()) || !std::isfinite(a.y()) || !std::isfinite(b.x()) || !std::isfinite(b.y()))
      fail(c.key, "coordinates must be finite numbers");
    const double length = std::hypot(b.x() - a.x(), b.y() - a.y());
    if (!(length > 0.0)) fail(c.key + "[" + std::to_string(k + 1) + "]", "repeats the point before it");
    start.push_back(start.back() + length);
  }
  const double n = std::floor(start.back() / dp + 1e-9);
  if (n < 1) fail(c.key, "is shorter than dp = " + number_text(dp) + " m");
  check_size(n, 1, fail);
  c.nx = int(n), c.ny = 1;
  c.origin = {t.section(0).x(), t.section(0).y()};
  std::size_t k = 0;
  for (int i = 0; i < c.nx; ++i) {
    const double s = (i + 0.5) * dp;
    while (k + 2 < start.size() && s > start[k + 1]) ++k;
    const pb::MapPoint &a = t.section(int(k)), &b = t.section(int(k) + 1);
    const double f = (s - start[k]) / (start[k + 1] - start[k]);
    c.points.push_back({a.x() + f * (b.x() - a.x()), a.y() + f * (b.y() - a.y())});
  }
  return c;
}

std::array<double, 4> bounds(const std::vector<MapPoint>& points) {
  std::array<double, 4> b{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                          -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const MapPoint& p : points)
    b = {std::min(b[0], p.x), std::min(b[1], p.y), std::max(b[2], p.x), std::max(b[3], p.y)};
  return b;
}

// One raster's values at the columns, or the case's error naming `file_key` or the columns' key.
std::vector<double> sample(const std::string& file_key, const std::string& file, const Columns& columns,
                           const TerrainFailure& fail, std::string* crs) {
  const std::array<double, 4> region = bounds(columns.points);
  std::optional<Raster> raster;
  try {
    raster = Raster::open(file, region);
  } catch (const RasterError& e) {
    fail(file_key, e.what());
  }
  const std::array<double, 4> extent = raster->extent();
  if (region[2] < extent[0] || region[0] > extent[2] || region[3] < extent[1] || region[1] > extent[3])
    fail(columns.key, "does not overlap " + file + ", whose extent is " + extent_text(extent));
  std::vector<double> values;
  values.reserve(columns.points.size());
  for (const MapPoint& p : columns.points) {
    if (!raster->covers(p.x, p.y))
      fail(columns.key, "reaches beyond " + file + " at map point " + map_point_text(p) + ": its extent is " +
                            extent_text(extent));
    const std::optional<double> z = raster->at(p.x, p.y);
    if (!z)
      fail(file_key, file + " has no data (nodata) at map point " + map_point_text(p) +
                         ", inside the case's terrain: fill the holes (e.g. gdal_fillnodata.py) or move the " +
                         (columns.ny > 1 ? "window" : "section"));
    values.push_back(*z);
  }
  *crs = raster->crs();
  return values;
}

bool same_crs(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty() || a == b) return true;
  OGRSpatialReference ra, rb;
  if (ra.importFromWkt(a.c_str()) != OGRERR_NONE || rb.importFromWkt(b.c_str()) != OGRERR_NONE) return false;
  return ra.IsSame(&rb);
}

}  // namespace

bool names_terrain_rasters(const pb::Terrain& t) {
  return !t.surface_file().empty() || !t.base_file().empty() || !t.thickness_file().empty() || t.thickness() != 0 ||
         t.has_window() || t.section_size() > 0;
}

void expand_terrain(pb::Terrain& terrain, int dimensions, double dp, const std::filesystem::path& case_directory,
                    const TerrainFailure& fail) {
  if (terrain.has_grid()) fail("terrain.grid", "is set by the loader from the rasters: leave it out of a case file");
  if (!(dp > 0.0) || !std::isfinite(dp)) fail("dp", "must be a positive number");
  if (terrain.surface_file().empty()) fail("terrain.surface_file", "is missing: the raster (GeoTIFF) of the ground's elevation");
  const int bases = int(!terrain.base_file().empty()) + int(!terrain.thickness_file().empty()) + int(terrain.thickness() != 0);
  if (bases != 1)
    fail("terrain", "needs the soil's base as exactly one of base_file (bedrock elevation), thickness_file or thickness");
  if (terrain.thickness() != 0 && !(terrain.thickness() > 0.0 && std::isfinite(terrain.thickness())))
    fail("terrain.thickness", "must be a positive number of metres (is " + number_text(terrain.thickness()) + ")");
  if (dimensions == 3 && terrain.section_size() > 0)
    fail("terrain.section", "is for 2D cases; a 3D case takes a window");
  if (dimensions == 2 && terrain.has_window()) fail("terrain.window", "is for 3D cases; a 2D case takes a section");
  if (dimensions != 2 && dimensions != 3) fail("dimensions", "must be 2 or 3 for a terrain");
  const Columns columns = dimensions == 3 ? window_columns(terrain, dp, fail) : section_columns(terrain, dp, fail);

  const auto path = [&](const std::string& name) { return (case_directory / name).lexically_normal().string(); };
  const std::string surface_path = path(terrain.surface_file());
  std::string crs, base_crs;
  const std::vector<double> surface = sample("terrain.surface_file", surface_path, columns, fail, &crs);
  std::vector<double> base;
  std::string base_key, base_source;
  if (!terrain.base_file().empty()) {
    base_key = "terrain.base_file", base_source = path(terrain.base_file());
    base = sample(base_key, base_source, columns, fail, &base_crs);
  } else if (!terrain.thickness_file().empty()) {
    base_key = "terrain.thickness_file", base_source = path(terrain.thickness_file());
    base = sample(base_key, base_source, columns, fail, &base_crs);
    for (std::size_t n = 0; n < base.size(); ++n) base[n] = surface[n] - base[n];
  } else {
    base_key = "terrain.thickness", base_source = number_text(terrain.thickness()) + " m below the surface";
    for (double z : surface) base.push_back(z - terrain.thickness());
  }
  if (!same_crs(crs, base_crs))
    fail(base_key, base_source + " is in another coordinate reference system than " + surface_path);
  for (std::size_t n = 0; n < surface.size(); ++n)
    if (base[n] > surface[n])
      fail(base_key, "puts the soil's base above the surface at map point " + map_point_text(columns.points[n]) +
                         ": base " + number_text(base[n]) + " m, surface " + number_text(surface[n]) + " m");

  pb::TerrainGrid& grid = *terrain.mutable_grid();
  grid.set_nx(columns.nx);
  grid.set_ny(columns.ny);
  for (std::size_t k = 0; k < surface.size(); ++k) grid.add_surface(surface[k]), grid.add_base(base[k]);
  grid.add_origin(columns.origin.x);
  grid.add_origin(columns.origin.y);
  grid.set_crs(crs);
  grid.set_surface_source(surface_path);
  grid.set_base_source(base_source);
  *grid.mutable_section() = terrain.section();
  terrain.clear_surface_file();
  terrain.clear_base_file();
  terrain.clear_thickness_file();
  terrain.clear_thickness();
  terrain.clear_window();
  terrain.clear_section();
}

namespace {

bool uses_terrain(const pb::ScenarioSpec& spec, std::string* key) {
  for (int i = 0; i < spec.bodies_size(); ++i) {
    const pb::Body& b = spec.bodies(i);
    const std::string body = "bodies[" + std::to_string(i) + "]";
    if (b.shape().has_terrain()) return *key = body + ".shape.terrain", true;
    for (int k = 0; k < b.subtract_size(); ++k)
      if (b.subtract(k).has_terrain()) return *key = body + ".subtract[" + std::to_string(k) + "].terrain", true;
  }
  return false;
}

}  // namespace

void check_terrain(const pb::ScenarioSpec& spec, const TerrainFailure& fail) {
  const pb::Terrain& t = spec.terrain();
  const std::string file_message =
      "names a raster input, which only the loader of a case file reads (cascade run, cascade create): a case sent "
      "as text, or a spec, carries terrain.grid instead";
  if (!t.surface_file().empty()) fail("terrain.surface_file", file_message);
  if (!t.base_file().empty()) fail("terrain.base_file", file_message);
  if (!t.thickness_file().empty()) fail("terrain.thickness_file", file_message);
  if (t.thickness() != 0) fail("terrain.thickness", file_message);
  if (t.has_window()) fail("terrain.window", file_message);
  if (t.section_size() > 0) fail("terrain.section", file_message);

  std::string user;
  if (uses_terrain(spec, &user) && !t.has_grid())
    fail(user, "the case has no terrain: give terrain.surface_file, its base and its window (3D) or section (2D)");
  if (!t.has_grid()) return;
  const pb::TerrainGrid& g = t.grid();
  const std::string key = "terrain.grid";
  if (g.nx() < 1 || g.ny() < 1) fail(key, "needs nx >= 1 and ny >= 1");
  if (spec.dimensions() == 2 && g.ny() != 1) fail(key + ".ny", "must be 1 in a 2D case (a section)");
  check_size(g.nx(), g.ny(), fail);
  const int n = g.nx() * g.ny();
  if (g.surface_size() != n) fail(key + ".surface", "needs nx · ny = " + std::to_string(n) + " heights");
  if (g.base_size() != n) fail(key + ".base", "needs nx · ny = " + std::to_string(n) + " heights");
  for (int k = 0; k < n; ++k) {
    if (!std::isfinite(g.surface(k)) || !std::isfinite(g.base(k))) fail(key, "heights must be finite numbers");
    if (g.base(k) > g.surface(k))
      fail(key + ".base", "is above the surface at column " + std::to_string(k) + ": base " + number_text(g.base(k)) +
                              " m, surface " + number_text(g.surface(k)) + " m");
  }
  if (g.origin_size() != 0 && g.origin_size() != 2) fail(key + ".origin", "needs [X, Y] or nothing");
}

LayerSurfaces layer_surfaces(const pb::TerrainLayer& layer, const pb::TerrainGrid& grid, int dimensions, double dp,
                             double bottom) {
  LayerSurfaces s;
  const auto extended = [dp](int n) {
    std::vector<double> x{0.0};
    for (int i = 0; i < n; ++i) x.push_back((i + 0.5) * dp);
    x.push_back(n * dp);
    return x;
  };
  s.x = extended(grid.nx());
  s.y = dimensions == 3 ? extended(grid.ny()) : std::vector<double>{0.0};
  const int nx = int(s.x.size()), ny = int(s.y.size());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      // The grid's node nearest the extended node: the edge nodes repeat the outermost ones.
      const int gi = std::clamp(i - 1, 0, grid.nx() - 1), gj = dimensions == 3 ? std::clamp(j - 1, 0, grid.ny() - 1) : 0;
      const double surface = grid.surface(gj * grid.nx() + gi), base = grid.base(gj * grid.nx() + gi);
      switch (layer.layer()) {
        case pb::BEDROCK:
          s.lower.push_back(bottom), s.upper.push_back(base);
          break;
        case pb::LAKE:
          s.lower.push_back(surface), s.upper.push_back(std::max(layer.level(), surface));
          break;
        default:
          s.lower.push_back(base), s.upper.push_back(surface);
      }
    }
  return s;
}

}  // namespace cascade
