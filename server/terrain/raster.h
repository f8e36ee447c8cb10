// Elevation rasters through GDAL (GeoTIFF, or any raster format GDAL reads): the values of band 1
// at map points, bilinear between pixel centres, and the writing of GeoTIFFs (the project's
// shipped terrain, the tests' rasters).
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace cascade {

// Why a raster could not be used; the caller names the case key.
class RasterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A north-up raster's band 1: the block of it around the map region the caller needs, read into
// memory (a LiDAR tile of 10⁸ pixels is not read whole for a window of 10⁴). Pixel (c, r) covers map X in
// [X0 + c dX, X0 + (c + 1) dX] and Y in [Y0 + (r + 1) dY, Y0 + r dY] (dY < 0, GDAL's geotransform);
// its value sits at the pixel's centre.
class Raster {
 public:
  // Reads the pixels that the map region [x_min, y_min, x_max, y_max] needs (the whole raster when
  // the region covers it). Throws RasterError: no such file, not a raster, no band, a rotated
  // geotransform.
  static Raster open(const std::string& path, const std::array<double, 4>& region);

  // The value at map point (x, y): bilinear between the four pixel centres around it, the nearest
  // edge pixels' in the outer half pixel. Nothing when the point is outside the raster or a pixel
  // it needs holds the nodata value.
  std::optional<double> at(double x, double y) const;
  bool covers(double x, double y) const;

  // The map extent: [x_min, y_min, x_max, y_max].
  std::array<double, 4> extent() const;
  const std::string& crs() const { return crs_; }  // WKT, empty when the raster has none
  const std::string& path() const { return path_; }

 private:
  std::string path_, crs_;
  int columns_ = 0, rows_ = 0;                     // the whole raster
  int block_column_ = 0, block_row_ = 0;           // the block in memory: its first pixel,
  int block_columns_ = 0, block_rows_ = 0;         // and its size
  double x0_ = 0.0, dx_ = 1.0, y0_ = 0.0, dy_ = -1.0;
  std::optional<double> nodata_;
  std::vector<double> values_;  // the block, row-major
};

// Writes a one-band Float32 GeoTIFF (deflate-compressed): `values` row-major from the top (north)
// row, pixel (0, 0)'s corner at map (x0, y0), square pixels of `pixel` metres, CRS from its EPSG
// code (0: none), nodata marked by `nodata` when given. Throws RasterError.
void write_geotiff(const std::string& path, int columns, int rows, double x0, double y0, double pixel,
                   const std::vector<double>& values, int epsg, std::optional<double> nodata = std::nullopt);

}  // namespace cascade
