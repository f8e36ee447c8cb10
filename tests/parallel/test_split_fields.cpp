// fields.h5 written by every process of a split run at once (server/io/split_fields_writer.h,
// issue 17): process 0 lays each frame out, every process writes its block of rows of each dataset
// with MPI-IO. Launched by ctest through mpirun at 1 to 4 processes (tests/CMakeLists.txt). The
// file read back with HDF5 holds, value for value and bit for bit, what one process writes of the
// same frames with Hdf5FieldWriter::write (there chunked and compressed: 10,007 particles, above
// kCompressAbove), the frames' times, steps and units included, and its XDMF sidecar is the same
// text; a process whose block is wrong fails, and the frame is taken out of the file and stays out
// of the sidecar, the next frame taking its place.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "server/core/field_frame.h"
#include "server/io/hdf5_writer.h"
#include "server/io/split_fields_writer.h"
#include "server/parallel/mpi_transport.h"
#include "tests/parallel/mpi_test_main.h"

namespace cascade {
namespace {

MpiTransport* world = nullptr;

constexpr std::size_t kParticles = 10007;

FieldFrame whole_frame(double time, std::uint64_t step) {
  FieldFrame f;
  f.time = time, f.step = step, f.dimensions = 3;
  FieldFrame::RealField pressure{"pressure", "Pa", 1, {}}, velocity{"velocity", "m/s", 3, {}};
  for (std::size_t i = 0; i < kParticles; ++i) {
    f.position.insert(f.position.end(), {1e-3 * double(i), double(i % 7), -std::sqrt(double(i)) - time});
    f.phase.push_back(std::uint8_t(i % 3));
    f.id.push_back(std::uint32_t(i));
    f.free_surface.push_back(std::uint8_t(i % 2));
    pressure.values.push_back(1e4 * std::sin(double(i)) + time);
    velocity.values.insert(velocity.values.end(), {double(i), time, -1.0 / (1.0 + double(i))});
  }
  f.fields = {pressure, velocity};
  return f;
}

// Rows first .. first + count of a frame.
FieldFrame rows_of(const FieldFrame& whole, std::size_t first, std::size_t count) {
  FieldFrame b;
  b.time = whole.time, b.step = whole.step, b.dimensions = whole.dimensions;
  b.position.assign(whole.position.begin() + std::ptrdiff_t(3 * first), whole.position.begin() + std::ptrdiff_t(3 * (first + count)));
  b.phase.assign(whole.phase.begin() + std::ptrdiff_t(first), whole.phase.begin() + std::ptrdiff_t(first + count));
  b.id.assign(whole.id.begin() + std::ptrdiff_t(first), whole.id.begin() + std::ptrdiff_t(first + count));
  b.free_surface.assign(whole.free_surface.begin() + std::ptrdiff_t(first),
                        whole.free_surface.begin() + std::ptrdiff_t(first + count));
  for (const auto& f : whole.fields)
    b.fields.push_back({f.name, f.units, f.components,
                        std::vector<double>(f.values.begin() + std::ptrdiff_t(first * f.components),
                                            f.values.begin() + std::ptrdiff_t((first + count) * f.components))});
  return b;
}

FieldFrame my_block(const FieldFrame& whole) {
  const int me = world->process(), processes = world->processes();
  const std::size_t first = id_block_start(kParticles, processes, me);
  return rows_of(whole, first, id_block_start(kParticles, processes, me + 1) - first);
}

void barrier() { world->exchange(std::vector<std::vector<char>>(std::size_t(world->processes()))); }

std::string text_of(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A dataset's bytes as stored (read in the file's own type) and its units.
std::vector<char> bytes_of(hid_t file, const std::string& path, std::string* units = nullptr) {
  const hid_t dataset = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(dataset, 0) << path;
  if (dataset < 0) return {};
  const hid_t type = H5Dget_type(dataset), space = H5Dget_space(dataset);
  std::vector<char> bytes(std::size_t(H5Sget_simple_extent_npoints(space)) * H5Tget_size(type));
  EXPECT_GE(H5Dread(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), 0) << path;
  if (units) {
    const hid_t attribute = H5Aopen(dataset, "units", H5P_DEFAULT), string_type = H5Aget_type(attribute);
    char* text = nullptr;  // a variable-length string (hdf5_support.h)
    EXPECT_GE(H5Aread(attribute, string_type, &text), 0) << path;
    units->assign(text ? text : "");
    H5free_memory(text);
    H5Tclose(string_type), H5Aclose(attribute);
  }
  H5Sclose(space), H5Tclose(type), H5Dclose(dataset);
  return bytes;
}

double attribute_of(hid_t file, const std::string& group, const char* name) {
  const hid_t g = H5Gopen2(file, group.c_str(), H5P_DEFAULT);
  const hid_t a = H5Aopen(g, name, H5P_DEFAULT);
  double value = std::nan("");
  H5Aread(a, H5T_NATIVE_DOUBLE, &value);
  H5Aclose(a), H5Gclose(g);
  return value;
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::path(CASCADE_BINARY_DIR) / "tests" / "parallel" /
                   ("split_fields_" + std::to_string(world->processes()));
  if (world->process() == 0) std::filesystem::create_directories(dir);
  barrier();
  return dir / name;
}

TEST(SplitFields, EveryProcessWritesItsBlockOfEachDatasetAsOneProcessWritesTheFrame) {
  const std::vector<FieldFrame> frames = {whole_frame(0.0, 0), whole_frame(0.25, 117)};
  const auto alone_path = scratch("alone.h5"), split_path = scratch("split.h5");
  if (world->process() == 0) {
    Hdf5FieldWriter alone(alone_path);
    for (const auto& f : frames) alone.write(f);
  }
  {
    std::unique_ptr<Hdf5FieldWriter> writer;
    if (world->process() == 0) writer = std::make_unique<Hdf5FieldWriter>(split_path);
    barrier();  // the file exists before any process opens it
    for (const auto& f : frames)
      EXPECT_EQ(write_split_frame(*world, writer.get(), split_path, my_block(f), kParticles), "");
    if (writer) EXPECT_EQ(writer->frames_written(), frames.size());
  }
  barrier();
  if (world->process() != 0) return;
  const hid_t alone = H5Fopen(alone_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t split = H5Fopen(split_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(alone, 0);
  ASSERT_GE(split, 0);
  std::vector<std::string> paths = {"/topology/polyvertex_" + std::to_string(kParticles)};
  for (const char* group : {"/frames/000000", "/frames/000001"}) {
    EXPECT_EQ(attribute_of(split, group, "time"), attribute_of(alone, group, "time")) << group;
    EXPECT_EQ(attribute_of(split, group, "step"), attribute_of(alone, group, "step")) << group;
    for (const char* d : {"position", "phase", "id", "free_surface", "pressure", "velocity"})
      paths.push_back(std::string(group) + "/" + d);
  }
  for (const auto& path : paths) {
    std::string units_alone, units_split;
    const std::vector<char> one = bytes_of(alone, path, &units_alone);
    EXPECT_GT(one.size(), kParticles - 1) << path;
    EXPECT_TRUE(one == bytes_of(split, path, &units_split)) << path << " differs";
    EXPECT_EQ(units_split, units_alone) << path;
  }
  H5Fclose(alone), H5Fclose(split);
  // The sidecars name their own files: alone.h5 for split.h5, and otherwise the same text.
  std::string sidecar = text_of(std::filesystem::path(alone_path).replace_extension(".xdmf"));
  for (std::size_t at = sidecar.find("alone.h5:"); at != std::string::npos; at = sidecar.find("alone.h5:", at))
    sidecar.replace(at, 8, "split.h5");
  EXPECT_EQ(text_of(std::filesystem::path(split_path).replace_extension(".xdmf")), sidecar);
  EXPECT_NE(sidecar.find("frame_000001"), std::string::npos);
}

TEST(SplitFields, AProcessWithAWrongBlockFailsAndTheFrameIsTakenOut) {
  const auto path = scratch("failing.h5");
  std::unique_ptr<Hdf5FieldWriter> writer;
  if (world->process() == 0) writer = std::make_unique<Hdf5FieldWriter>(path);
  barrier();
  const FieldFrame whole = whole_frame(0.5, 3);
  FieldFrame block = my_block(whole);
  const bool wrong = world->process() == world->processes() - 1;
  if (wrong) block = rows_of(whole, 0, block.size() - 1);  // a row short
  const std::string failure = write_split_frame(*world, writer.get(), path, block, kParticles);
  if (wrong) EXPECT_NE(failure.find("not its share of the ids"), std::string::npos) << failure;
  if (writer) {
    EXPECT_EQ(writer->frames_written(), 0u);
    EXPECT_EQ(text_of(std::filesystem::path(path).replace_extension(".xdmf")).find("frame_000000"), std::string::npos);
  }
  // The next frame, whole, takes its place.
  EXPECT_EQ(write_split_frame(*world, writer.get(), path, my_block(whole), kParticles), "");
  if (!writer) return;
  EXPECT_EQ(writer->frames_written(), 1u);
  writer->close();
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const std::vector<char> ids = bytes_of(file, "/frames/000000/id");
  ASSERT_EQ(ids.size(), kParticles * sizeof(std::uint32_t));
  std::vector<std::uint32_t> id(kParticles);
  std::memcpy(id.data(), ids.data(), ids.size());
  for (std::size_t i = 0; i < kParticles; ++i) ASSERT_EQ(id[i], i);
  H5Fclose(file);
}

}  // namespace
}  // namespace cascade

int main(int argc, char** argv) { return cascade::testing::mpi_test_main(argc, argv, cascade::world); }
