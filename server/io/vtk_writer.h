// VTK XML output: one frame_NNNNNN.vtp (vtkPolyData, a vertex cell per particle) per frame and a
// frames.pvd collection that ParaView opens as a time series. For single frames and small runs;
// fields.h5 is the format for long series of large frames (docs/output.md).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "server/core/field_frame.h"

namespace cascade {

struct VtkWriterOptions {
  // zlib inside the appended binary data: about half the size, about 30 times slower to write
  // (notes/PLATFORM.md: 2.8 s against 0.1 s for a million particles).
  bool compress = false;
};

class VtkSeriesWriter {
 public:
  // Creates `directory` if needed. Frames already there from an earlier run are overwritten
  // as the new run reaches them; frames.pvd lists only this run's frames.
  explicit VtkSeriesWriter(std::filesystem::path directory, VtkWriterOptions options = {});

  // Writes frame_NNNNNN.vtp (NNNNNN = frames_written() before the call) and rewrites frames.pvd
  // atomically. Returns the .vtp path. Throws std::invalid_argument on inconsistent sizes and
  // std::runtime_error when VTK cannot write the file.
  std::filesystem::path write(const FieldFrame& frame);

  std::size_t frames_written() const { return entries_.size(); }
  std::filesystem::path pvd_path() const { return directory_ / "frames.pvd"; }

 private:
  std::filesystem::path directory_;
  VtkWriterOptions options_;
  std::vector<std::string> entries_;  // rendered <DataSet .../> lines of frames.pvd
};

}  // namespace cascade
