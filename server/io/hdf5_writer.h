// fields.h5: every output frame of a run in one HDF5 file, one group per frame, with the XDMF
// sidecar (fields.xdmf) that ParaView opens. Layout in docs/output.md. The HDF5 headers stay in
// the .cpp file, so including this header needs no HDF5 include path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "server/core/field_frame.h"
#include "server/io/xdmf_writer.h"

namespace cascade {

class Hdf5FieldWriter {
 public:
  // Frames with more particles than this are stored chunked and gzip-compressed.
  static constexpr std::size_t kCompressAbove = 4096;

  // Creates (or truncates) `h5_path` and its sidecar, the same path with extension .xdmf.
  // `fields_filter` lists the named fields to write (an empty list writes all of them): the
  // frame's RealFields and free_surface; position, phase and id are always written. Throws
  // std::runtime_error if the file cannot be created.
  explicit Hdf5FieldWriter(const std::filesystem::path& h5_path,
                           std::vector<std::string> fields_filter = {});
  ~Hdf5FieldWriter();
  Hdf5FieldWriter(const Hdf5FieldWriter&) = delete;
  Hdf5FieldWriter& operator=(const Hdf5FieldWriter&) = delete;

  // Appends the frame as group /frames/NNNNNN (NNNNNN = frames_written() before the call),
  // flushes the file and rewrites the sidecar, so a run killed later leaves this frame readable.
  // Throws std::invalid_argument, naming the array, if the frame's sizes are inconsistent.
  void write(const FieldFrame& frame);

  // A frame that the processes of a split run write themselves, each its rows (in id order):
  // where the rows of one of its datasets lie in the file.
  struct ReservedDataset {
    std::string column;     // "position", "phase", "id", "free_surface", a field's name, or "topology"
                            // (the Polyvertex connectivity 0 … N−1, written once per particle count)
    std::uint64_t offset;   // of row 0 in the file
    std::size_t row_bytes;  // little-endian: float64 × components, uint32 (id, topology), uint8
  };
  // Appends a frame of `particles` rows as write() does, with its datasets contiguous,
  // uncompressed and allocated but not written (no fill either), and returns where their rows lie
  // (none for no particles). `shape` gives the time, step, dimensions and fields; its rows are not
  // written. The frame enters the sidecar at commit_reserved(), once the rows are in the file.
  std::vector<ReservedDataset> reserve(const FieldFrame& shape, std::size_t particles);
  void commit_reserved();
  // Takes the reserved frame out of the file again (a process could not write its rows).
  void abandon_reserved();

  // Closes the file; later writes throw std::logic_error. The destructor calls it.
  void close();

  std::size_t frames_written() const { return frames_; }
  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& xdmf_path() const { return xdmf_.path(); }

 private:
  bool selected(const std::string& field_name) const;
  std::string connectivity_dataset(std::size_t particles, std::vector<ReservedDataset>* reserved);
  void add_frame(const FieldFrame& frame, std::size_t particles, std::vector<ReservedDataset>* reserved);

  std::filesystem::path path_;
  std::vector<std::string> fields_filter_;
  std::int64_t file_ = -1;  // hid_t of the open file, -1 once closed
  std::size_t frames_ = 0;
  int dimensions_ = 0;                             // of the first frame; every frame must match it
  std::vector<std::size_t> connectivity_written_;  // particle counts with a /topology dataset
  XdmfWriter xdmf_;
  std::optional<XdmfWriter::Grid> pending_;  // of the frame added and not yet committed
  std::optional<std::string> pending_topology_;  // a connectivity dataset laid out with it
};

}  // namespace cascade
