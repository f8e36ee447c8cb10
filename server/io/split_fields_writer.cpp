#include "server/io/split_fields_writer.h"

#include <cstdint>
#include <cstring>
#include <exception>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace cascade {
namespace {

// The layout as a message: per dataset its column's name, its offset and its row's bytes.
std::vector<char> layout_message(const std::vector<Hdf5FieldWriter::ReservedDataset>& reserved) {
  std::vector<char> bytes;
  const auto put = [&](const void* data, std::size_t size) {
    bytes.insert(bytes.end(), static_cast<const char*>(data), static_cast<const char*>(data) + size);
  };
  const std::uint64_t count = reserved.size();
  put(&count, sizeof count);
  for (const auto& d : reserved) {
    const std::uint64_t name = d.column.size(), row = d.row_bytes;
    put(&name, sizeof name);
    put(d.column.data(), d.column.size());
    put(&d.offset, sizeof d.offset);
    put(&row, sizeof row);
  }
  return bytes;
}

std::vector<Hdf5FieldWriter::ReservedDataset> read_layout(const std::vector<char>& bytes) {
  std::size_t at = 0;
  const auto take = [&](void* data, std::size_t size) {
    if (size > bytes.size() - at) throw std::invalid_argument("a frame's layout in fields.h5 ends early");
    std::memcpy(data, bytes.data() + at, size);
    at += size;
  };
  std::uint64_t count = 0;
  take(&count, sizeof count);
  std::vector<Hdf5FieldWriter::ReservedDataset> reserved;
  for (; count > 0; --count) {
    Hdf5FieldWriter::ReservedDataset d;
    std::uint64_t name = 0, row = 0;
    take(&name, sizeof name);
    if (name > bytes.size() - at) throw std::invalid_argument("a frame's layout in fields.h5 ends early");
    d.column.resize(name);
    take(d.column.data(), name);
    take(&d.offset, sizeof d.offset);
    take(&row, sizeof row);
    d.row_bytes = row;
    reserved.push_back(std::move(d));
  }
  return reserved;
}

}  // namespace

std::string write_split_frame(Transport& transport, Hdf5FieldWriter* writer, const std::filesystem::path& h5_path,
                              const FieldFrame& block, std::size_t particles) {
  const int me = transport.process(), processes = transport.processes();
  std::string failure;
  std::vector<std::vector<char>> send(static_cast<std::size_t>(processes));
  if (me == 0) {
    try {
      if (!writer) throw std::logic_error("process 0 has no writer of " + h5_path.string());
      const std::vector<char> layout = layout_message(writer->reserve(block, particles));
      for (auto& message : send) message = layout;
    } catch (const std::exception& e) {
      failure = e.what();
    }
  }
  const auto received = transport.exchange(send);
  if (received[0].empty())  // process 0 could not lay the frame out: no process writes
    return failure.empty() ? "process 0 could not lay out a frame in " + h5_path.string() : failure;

  const std::size_t first_row = id_block_start(particles, processes, me);
  std::vector<std::uint32_t> topology(block.size());  // the Polyvertex connectivity: row numbers
  std::iota(topology.begin(), topology.end(), std::uint32_t(first_row));
  std::vector<Transport::FilePiece> pieces;
  try {
    if (block.size() != id_block_start(particles, processes, me + 1) - first_row)
      throw std::logic_error("process " + std::to_string(me) + "'s block holds " + std::to_string(block.size()) +
                             " particles, not its share of the ids");
    for (const auto& d : read_layout(received[0])) {
      const void* rows = nullptr;
      std::size_t row_bytes = 0;  // in memory
      if (d.column == "position") rows = block.position.data(), row_bytes = 3 * sizeof(double);
      else if (d.column == "phase") rows = block.phase.data(), row_bytes = 1;
      else if (d.column == "id") rows = block.id.data(), row_bytes = sizeof(std::uint32_t);
      else if (d.column == "free_surface") rows = block.free_surface.data(), row_bytes = 1;
      else if (d.column == "topology") rows = topology.data(), row_bytes = sizeof(std::uint32_t);
      else if (const auto* field = block.find(d.column))
        rows = field->values.data(), row_bytes = std::size_t(field->components) * sizeof(double);
      if (block.size() == 0) continue;
      if (!rows || row_bytes != d.row_bytes)
        throw std::logic_error("fields.h5's dataset '" + d.column + "' does not match the frame's rows");
      pieces.push_back({d.offset + first_row * d.row_bytes, rows, block.size() * d.row_bytes});
    }
  } catch (const std::exception& e) {
    failure = e.what();
    pieces.clear();
  }
  try {
    transport.write_pieces(h5_path.string(), pieces);
  } catch (const std::exception& e) {
    if (failure.empty()) failure = e.what();
  }
  const bool written = transport.maximum(failure.empty() ? 0.0 : 1.0) == 0;
  if (me == 0) {
    try {
      if (written) writer->commit_reserved();
      else writer->abandon_reserved();
    } catch (const std::exception& e) {
      if (failure.empty()) failure = e.what();
    }
  }
  return failure;
}

}  // namespace cascade
