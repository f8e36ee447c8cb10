#include "server/io/hdf5_writer.h"

#include <hdf5.h>

#include "server/io/hdf5_support.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace cascade {
namespace {

using namespace hdf5;

static_assert(std::is_same_v<hid_t, std::int64_t>, "file_ stores an hid_t");

constexpr char kFormat[] = "cascade-fields-1";

// Writes rows x components values as a dataset of shape (rows) or (rows, components), chunked
// and compressed when there are more than kCompressAbove rows. With no values (`data` null) the
// dataset is laid out contiguous and its space allocated at once, unfilled, for others to write
// into (Hdf5FieldWriter::reserve): returns where its first row lies in the file (0 for no rows).
std::uint64_t write_dataset(hid_t group, const std::string& name, hid_t file_type, hid_t memory_type,
                            std::size_t rows, int components, const void* data, const std::string& units) {
  const int rank = components == 1 ? 1 : 2;
  const hsize_t dims[2] = {rows, static_cast<hsize_t>(components)};
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose, "create space of " + name);
  Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "create properties of " + name);
  if (!data) {
    check(H5Pset_layout(properties, H5D_CONTIGUOUS), "lay out " + name);
    check(H5Pset_alloc_time(properties, H5D_ALLOC_TIME_EARLY), "allocate " + name);
    check(H5Pset_fill_time(properties, H5D_FILL_TIME_NEVER), "leave " + name + " unfilled");
  } else if (rows > Hdf5FieldWriter::kCompressAbove) {
    // About 1 MiB per chunk: large enough for gzip, small enough to read a slice cheaply.
    const std::size_t row_bytes = H5Tget_size(file_type) * static_cast<std::size_t>(components);
    const hsize_t chunk[2] = {
        std::min<hsize_t>(rows, std::max<std::size_t>(1, (1u << 20) / row_bytes)),
        static_cast<hsize_t>(components)};
    check(H5Pset_chunk(properties, rank, chunk), "chunk " + name);
    if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
      check(H5Pset_shuffle(properties), "shuffle " + name);  // byte planes compress far better
      check(H5Pset_deflate(properties, 1), "compress " + name);
    }
  }
  Handle dataset(
      H5Dcreate2(group, name.c_str(), file_type, space, H5P_DEFAULT, properties, H5P_DEFAULT),
      H5Dclose, "create dataset " + name);
  if (data && rows > 0)
    check(H5Dwrite(dataset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + name);
  write_string_attribute(dataset, "units", units);
  if (data || rows == 0) return 0;
  const haddr_t offset = H5Dget_offset(dataset);
  if (offset == HADDR_UNDEF) throw std::runtime_error("HDF5: no place in the file for " + name);
  return offset;
}

// Datasets of FieldFrame's own members; a RealField may not take their names.
bool is_reserved(const std::string& name) {
  return name == "position" || name == "phase" || name == "id" || name == "free_surface";
}

void validate(const FieldFrame& frame) {
  const std::size_t n = frame.size();
  if (frame.dimensions < 1 || frame.dimensions > 3)
    throw std::invalid_argument("frame dimensions must be 1, 2 or 3, not " +
                                std::to_string(frame.dimensions));
  if (frame.position.size() != 3 * n)
    throw std::invalid_argument("position has " + std::to_string(frame.position.size()) +
                                " values, expected 3 x " + std::to_string(n));
  if (frame.phase.size() != n)
    throw std::invalid_argument("phase has " + std::to_string(frame.phase.size()) +
                                " values, expected " + std::to_string(n));
  if (!frame.free_surface.empty() && frame.free_surface.size() != n)
    throw std::invalid_argument("free_surface has " + std::to_string(frame.free_surface.size()) +
                                " values, expected " + std::to_string(n) + " or none");
  for (std::size_t i = 0; i < frame.fields.size(); ++i) {
    const FieldFrame::RealField& f = frame.fields[i];
    if (f.name.empty() || f.name == "." || f.name.find('/') != std::string::npos ||
        is_reserved(f.name))
      throw std::invalid_argument("field name '" + f.name + "' is not allowed");
    for (std::size_t j = 0; j < i; ++j)
      if (frame.fields[j].name == f.name)
        throw std::invalid_argument("field '" + f.name + "' appears twice");
    if (f.components < 1 || f.values.size() != n * static_cast<std::size_t>(f.components))
      throw std::invalid_argument("field '" + f.name + "' has " + std::to_string(f.values.size()) +
                                  " values, expected " + std::to_string(f.components) + " x " +
                                  std::to_string(n));
  }
}

std::string frame_group_name(std::size_t frame) {
  char name[32];
  std::snprintf(name, sizeof name, "/frames/%06zu", frame);
  return name;
}

}  // namespace

Hdf5FieldWriter::Hdf5FieldWriter(const std::filesystem::path& h5_path,
                                 std::vector<std::string> fields_filter)
    : path_(h5_path),
      fields_filter_(std::move(fields_filter)),
      xdmf_(std::filesystem::path(h5_path).replace_extension(".xdmf"),
            h5_path.filename().string()) {
  if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path());
  const hid_t file = H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("HDF5: cannot create " + path_.string());
  file_ = file;
  try {
    write_string_attribute(file, "format", kFormat);
    Handle frames(H5Gcreate2(file, "/frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                  "create /frames in " + path_.string());
    check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path_.string());
  } catch (...) {
    H5Fclose(file);
    throw;
  }
}

Hdf5FieldWriter::~Hdf5FieldWriter() {
  if (file_ >= 0) H5Fclose(file_);
}

void Hdf5FieldWriter::close() {
  if (file_ < 0) return;
  const herr_t status = H5Fclose(file_);
  file_ = -1;
  check(status, "close " + path_.string());
}

bool Hdf5FieldWriter::selected(const std::string& field_name) const {
  return fields_filter_.empty() || std::find(fields_filter_.begin(), fields_filter_.end(),
                                             field_name) != fields_filter_.end();
}

// One dataset 0 … N-1 per particle count, shared by every frame with that count: the explicit
// vertex connectivity of the XDMF Polyvertex topology.
std::string Hdf5FieldWriter::connectivity_dataset(std::size_t particles, std::vector<ReservedDataset>* reserved) {
  const std::string name = "/topology/polyvertex_" + std::to_string(particles);
  if (std::find(connectivity_written_.begin(), connectivity_written_.end(), particles) !=
      connectivity_written_.end())
    return name;
  if (H5Lexists(file_, "/topology", H5P_DEFAULT) <= 0) {
    Handle group(H5Gcreate2(file_, "/topology", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "create /topology");
  }
  std::vector<std::uint32_t> indices(reserved ? 0 : particles);
  std::iota(indices.begin(), indices.end(), 0u);
  const std::uint64_t offset = write_dataset(file_, name, H5T_STD_U32LE, H5T_NATIVE_UINT32, particles, 1,
                                             reserved ? nullptr : indices.data(), "1");
  if (reserved && particles > 0) reserved->push_back({"topology", offset, sizeof(std::uint32_t)});
  if (reserved) pending_topology_ = name;
  connectivity_written_.push_back(particles);
  return name;
}

void Hdf5FieldWriter::write(const FieldFrame& frame) {
  validate(frame);
  add_frame(frame, frame.size(), nullptr);
  commit_reserved();
}

std::vector<Hdf5FieldWriter::ReservedDataset> Hdf5FieldWriter::reserve(const FieldFrame& shape,
                                                                       std::size_t particles) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the processes write their rows in the file's byte order");
  validate(shape);
  std::vector<ReservedDataset> reserved;
  add_frame(shape, particles, &reserved);
  return reserved;
}

void Hdf5FieldWriter::commit_reserved() {
  if (!pending_) throw std::logic_error("no frame of " + path_.string() + " to commit");
  xdmf_.append(*pending_);
  pending_.reset();
  pending_topology_.reset();
  ++frames_;
}

// The group goes (its space stays in the file, unused), and the connectivity dataset laid out
// with it; the next frame takes the group's name.
void Hdf5FieldWriter::abandon_reserved() {
  if (!pending_) return;
  const std::string group_name = frame_group_name(frames_);
  pending_.reset();
  check(H5Ldelete(file_, group_name.c_str(), H5P_DEFAULT), "delete " + group_name);
  if (pending_topology_) {
    check(H5Ldelete(file_, pending_topology_->c_str(), H5P_DEFAULT), "delete " + *pending_topology_);
    connectivity_written_.pop_back();
    pending_topology_.reset();
  }
  check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush " + path_.string());
}

// The frame's group and datasets of n rows, with the frame's values or (`reserved`) laid out for
// the processes to write; flushed. The sidecar's grid waits in pending_.
void Hdf5FieldWriter::add_frame(const FieldFrame& frame, std::size_t n, std::vector<ReservedDataset>* reserved) {
  if (file_ < 0) throw std::logic_error("write to closed " + path_.string());
  if (pending_) throw std::logic_error("a frame of " + path_.string() + " is not committed");
  if (dimensions_ == 0) {  // the first frame (a frame taken out again leaves the attribute)
    dimensions_ = frame.dimensions;
    write_scalar_attribute(file_, "dimensions", H5T_STD_I32LE, H5T_NATIVE_INT, &dimensions_);
  } else if (frame.dimensions != dimensions_) {
    throw std::invalid_argument("frame has dimensions " + std::to_string(frame.dimensions) +
                                ", earlier frames " + std::to_string(dimensions_));
  }

  const std::string group_name = frame_group_name(frames_);
  XdmfWriter::Grid grid;
  grid.time = frame.time;
  grid.nodes = n;
  grid.connectivity_dataset = connectivity_dataset(n, reserved);
  grid.position_dataset = group_name + "/position";
  {
    Handle group(H5Gcreate2(file_, group_name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Gclose, "create " + group_name);
    write_scalar_attribute(group, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &frame.time);
    write_scalar_attribute(group, "step", H5T_STD_U64LE, H5T_NATIVE_UINT64, &frame.step);
    const auto put = [&](const std::string& name, hid_t file_type, hid_t memory_type, int components,
                         const void* data, const std::string& units) {
      const std::uint64_t offset =
          write_dataset(group, name, file_type, memory_type, n, components, reserved ? nullptr : data, units);
      if (reserved && n > 0)
        reserved->push_back({name, offset, H5Tget_size(file_type) * static_cast<std::size_t>(components)});
    };
    put("position", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, frame.position.data(), "m");
    put("phase", H5T_STD_U8LE, H5T_NATIVE_UINT8, 1, frame.phase.data(), "1");
    put("id", H5T_STD_U32LE, H5T_NATIVE_UINT32, 1, frame.id.data(), "1");
    grid.attributes.push_back({"phase", group_name + "/phase", 1, XdmfWriter::NumberType::uint8});
    grid.attributes.push_back({"id", group_name + "/id", 1, XdmfWriter::NumberType::uint32});
    if (!frame.free_surface.empty() && selected("free_surface")) {
      put("free_surface", H5T_STD_U8LE, H5T_NATIVE_UINT8, 1, frame.free_surface.data(), "1");
      grid.attributes.push_back(
          {"free_surface", group_name + "/free_surface", 1, XdmfWriter::NumberType::uint8});
    }
    for (const FieldFrame::RealField& f : frame.fields) {
      if (!selected(f.name)) continue;
      put(f.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, f.components, f.values.data(), f.units);
      grid.attributes.push_back(
          {f.name, group_name + "/" + f.name, f.components, XdmfWriter::NumberType::float64});
    }
  }
  check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush " + path_.string());
  pending_ = std::move(grid);
}

}  // namespace cascade
