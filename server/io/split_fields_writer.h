// fields.h5 of a run split over processes, written by all of them (issue 17): process 0 lays each
// frame out in the file (Hdf5FieldWriter::reserve: contiguous datasets, allocated, not written)
// and tells every process where the datasets lie; each process writes its block of rows of each
// (Engine::frame_block, in id order) with Transport::write_pieces (MPI-IO); the frame enters the
// sidecar once every process has written. No process holds more than its block, and the writes
// go to the file system from every process at once, as parallel HDF5's would (Debian's parallel
// HDF5 cannot be linked beside the serial one that GDAL and VTK bring: notes/PLATFORM.md).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "server/core/field_frame.h"
#include "server/core/partition.h"
#include "server/io/hdf5_writer.h"

namespace cascade {

// Collective: every process calls it with its block of the frame of `particles` particles;
// `writer` is process 0's writer of `h5_path` (null on the others). Returns what failed on this
// process, or "" (the frame is then in the file and its sidecar on every process's word; after a
// failure anywhere no process writes, or the frame is left out of the sidecar).
std::string write_split_frame(Transport& transport, Hdf5FieldWriter* writer, const std::filesystem::path& h5_path,
                              const FieldFrame& block, std::size_t particles);

}  // namespace cascade
