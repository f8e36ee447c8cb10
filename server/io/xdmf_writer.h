// XDMF 3 sidecar of fields.h5: the light XML that lets ParaView (Xdmf3ReaderT, XDMF Reader) and
// VisIt read the particle frames as a temporal collection of point grids. The heavy data stays in
// the HDF5 file; this file only names datasets in it by relative path ("fields.h5:/frames/...").
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace cascade {

class XdmfWriter {
 public:
  enum class NumberType { float64, uint8, uint32 };

  // One HDF5 dataset of a frame, shown as a node-centred attribute.
  struct Attribute {
    std::string name;
    std::string dataset;  // absolute path inside the HDF5 file
    int components = 1;   // 1 Scalar, 3 Vector, 9 Tensor, others (6 included) Matrix
    NumberType type = NumberType::float64;
  };

  struct Grid {
    double time = 0.0;
    std::size_t nodes = 0;
    std::string position_dataset;      // N × 3 float64
    std::string connectivity_dataset;  // N uint32: 0 … N-1 (one vertex cell per particle)
    std::vector<Attribute> attributes;
  };

  // `h5_file_name` is the name written into every reference, relative to the XDMF file's folder.
  // A file at `xdmf_path` is removed: the first append writes the new one.
  XdmfWriter(std::filesystem::path xdmf_path, std::string h5_file_name);

  // Adds one grid (time step) and rewrites the whole file atomically.
  void append(const Grid& grid);

  const std::filesystem::path& path() const { return path_; }

 private:
  std::string data_item(const std::string& dimensions, NumberType type,
                        const std::string& dataset) const;

  std::filesystem::path path_;
  std::string h5_file_name_;
  std::string grids_;  // the rendered <Grid> elements written so far
  std::size_t grid_count_ = 0;
};

}  // namespace cascade
