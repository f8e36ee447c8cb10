#include "server/terrain/raster.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <mutex>

namespace cascade {
namespace {

void register_drivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

// GDAL's own message for the last failure, its handler kept quiet (no lines on stderr).
class QuietGdal {
 public:
  QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler), CPLErrorReset(); }
  ~QuietGdal() { CPLPopErrorHandler(); }
  static std::string last() {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? std::string(": ") + m : std::string();
  }
};

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using DatasetHandle = std::unique_ptr<GDALDataset, DatasetCloser>;

}  // namespace

Raster Raster::open(const std::string& path, const std::array<double, 4>& region) {
  register_drivers();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw RasterError("no such file: " + path);
  QuietGdal quiet;
  DatasetHandle data(static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly)));
  if (!data) throw RasterError(path + " is not a raster GDAL can read" + QuietGdal::last());
  if (data->GetRasterCount() < 1) throw RasterError(path + " has no raster band");
  double gt[6];
  if (data->GetGeoTransform(gt) != CE_None)
    throw RasterError(path + " has no geotransform: its pixels have no map coordinates");
  if (gt[2] != 0.0 || gt[4] != 0.0 || !(gt[1] > 0.0) || !(gt[5] < 0.0))
    throw RasterError(path + " is not north-up (a rotated or flipped geotransform): warp it first, e.g. gdalwarp");
  Raster r;
  r.path_ = path;
  r.columns_ = data->GetRasterXSize();
  r.rows_ = data->GetRasterYSize();
  r.x0_ = gt[0], r.dx_ = gt[1], r.y0_ = gt[3], r.dy_ = gt[5];
  if (const char* wkt = data->GetProjectionRef()) r.crs_ = wkt;
  GDALRasterBand* band = data->GetRasterBand(1);
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  if (has_nodata) r.nodata_ = nodata;
  // The pixels around the region, one more on each side for the bilinear interpolation.
  const auto first = [](double pixel, int size) { return std::clamp(int(std::floor(pixel)) - 1, 0, size); };
  const auto last = [](double pixel, int size) { return std::clamp(int(std::ceil(pixel)) + 1, 0, size); };
  r.block_column_ = first((region[0] - r.x0_) / r.dx_, r.columns_);
  r.block_row_ = first((region[3] - r.y0_) / r.dy_, r.rows_);
  r.block_columns_ = last((region[2] - r.x0_) / r.dx_, r.columns_) - r.block_column_;
  r.block_rows_ = last((region[1] - r.y0_) / r.dy_, r.rows_) - r.block_row_;
  if (r.block_columns_ <= 0 || r.block_rows_ <= 0) return r;  // the region misses the raster
  r.values_.resize(std::size_t(r.block_columns_) * std::size_t(r.block_rows_));
  if (band->RasterIO(GF_Read, r.block_column_, r.block_row_, r.block_columns_, r.block_rows_, r.values_.data(),
                     r.block_columns_, r.block_rows_, GDT_Float64, 0, 0) != CE_None)
    throw RasterError("cannot read the pixels of " + path + QuietGdal::last());
  return r;
}

bool Raster::covers(double x, double y) const {
  const double c = (x - x0_) / dx_, r = (y - y0_) / dy_;
  return c >= 0.0 && c <= columns_ && r >= 0.0 && r <= rows_;
}

std::optional<double> Raster::at(double x, double y) const {
  if (!covers(x, y)) return std::nullopt;
  // Pixel-centre coordinates, clamped so that the outer half pixel takes the edge pixels' values.
  const double c = std::clamp((x - x0_) / dx_ - 0.5, 0.0, double(columns_ - 1));
  const double r = std::clamp((y - y0_) / dy_ - 0.5, 0.0, double(rows_ - 1));
  const int c0 = std::min(int(c), columns_ - 1), r0 = std::min(int(r), rows_ - 1);
  const int c1 = std::min(c0 + 1, columns_ - 1), r1 = std::min(r0 + 1, rows_ - 1);
  const double u = c - c0, v = r - r0;
  double z[2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const int row = (a ? r1 : r0) - block_row_, column = (b ? c1 : c0) - block_column_;
      if (row < 0 || row >= block_rows_ || column < 0 || column >= block_columns_)
        throw RasterError("Raster::at: (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the block read");
      const double value = values_[std::size_t(row) * std::size_t(block_columns_) + std::size_t(column)];
      if (!std::isfinite(value) || (nodata_ && value == *nodata_)) return std::nullopt;
      z[a][b] = value;
    }
  return (1 - v) * ((1 - u) * z[0][0] + u * z[0][1]) + v * ((1 - u) * z[1][0] + u * z[1][1]);
}

std::array<double, 4> Raster::extent() const {
  return {x0_, y0_ + rows_ * dy_, x0_ + columns_ * dx_, y0_};
}

void write_geotiff(const std::string& path, int columns, int rows, double x0, double y0, double pixel,
                   const std::vector<double>& values, int epsg, std::optional<double> nodata) {
  register_drivers();
  QuietGdal quiet;
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!driver) throw RasterError("GDAL has no GTiff driver");
  if (values.size() != std::size_t(columns) * std::size_t(rows))
    throw RasterError("write_geotiff: " + std::to_string(values.size()) + " values for " + std::to_string(columns) +
                      " × " + std::to_string(rows) + " pixels");
  char** options = nullptr;
  options = CSLSetNameValue(options, "COMPRESS", "DEFLATE");
  options = CSLSetNameValue(options, "PREDICTOR", "3");  // floating-point predictor: smooth terrain compresses well
  DatasetHandle data(driver->Create(path.c_str(), columns, rows, 1, GDT_Float32, options));
  CSLDestroy(options);
  if (!data) throw RasterError("cannot create " + path + QuietGdal::last());
  double gt[6] = {x0, pixel, 0.0, y0, 0.0, -pixel};
  data->SetGeoTransform(gt);
  if (epsg != 0) {
    OGRSpatialReference crs;
    if (crs.importFromEPSG(epsg) != OGRERR_NONE) throw RasterError("unknown EPSG code " + std::to_string(epsg));
    data->SetSpatialRef(&crs);
  }
  GDALRasterBand* band = data->GetRasterBand(1);
  if (nodata) band->SetNoDataValue(*nodata);
  std::vector<double> buffer = values;
  if (band->RasterIO(GF_Write, 0, 0, columns, rows, buffer.data(), columns, rows, GDT_Float64, 0, 0) != CE_None)
    throw RasterError("cannot write " + path + QuietGdal::last());
}

}  // namespace cascade
