// Write-then-read round trips for every output file of docs/output.md: fields.h5 read back with
// the HDF5 C API, fields.xdmf checked against the HDF5 file it references, .vtp/.pvd read back
// with VTK's XML readers, probes.csv and run.json parsed back.
#include <gtest/gtest.h>

#if __has_include(<hdf5.h>)
#include <hdf5.h>
#else
#include <hdf5/serial/hdf5.h>  // Debian's serial HDF5; cascade_io keeps its include path private
#endif

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedIntArray.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUtilities.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "server/core/field_frame.h"
#include "server/io/hdf5_writer.h"
#include "server/io/probe_csv_writer.h"
#include "server/io/run_summary.h"
#include "server/io/vtk_writer.h"

namespace cascade {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Synthetic frames

fs::path fresh_directory() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(CASCADE_BINARY_DIR) / "test_output" / "output_files" /
                       (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Values with full mantissas, plus NaN, -0 and a subnormal, so any conversion or rounding on the
// way to the file shows up in a bitwise comparison.
FieldFrame make_frame(std::size_t n, int dimensions, double time, std::uint64_t step,
                      bool with_stress, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(-2.0, 2.0);
  FieldFrame frame;
  frame.time = time;
  frame.step = step;
  frame.dimensions = dimensions;
  for (std::size_t i = 0; i < n; ++i) {
    frame.position.push_back(uniform(random));
    frame.position.push_back(dimensions == 3 ? uniform(random) : 0.0);
    frame.position.push_back(uniform(random));
    frame.phase.push_back(static_cast<std::uint8_t>(i % 3));
    frame.id.push_back(static_cast<std::uint32_t>(4000000000u - 7 * i));
  }
  const auto field = [&](const char* name, const char* units, int components) {
    FieldFrame::RealField f{name, units, components, {}};
    for (std::size_t k = 0; k < n * components; ++k) f.values.push_back(uniform(random) * 1e3);
    return f;
  };
  frame.fields.push_back(field("velocity", "m/s", 3));
  frame.fields.push_back(field("pressure", "Pa", 1));
  frame.fields.push_back(field("density", "kg/m^3", 1));
  if (with_stress) frame.fields.push_back(field("stress", "Pa", 6));
  std::vector<double>& pressure = frame.fields[1].values;
  if (n >= 3) {
    pressure[0] = std::numeric_limits<double>::quiet_NaN();
    pressure[1] = -0.0;
    pressure[2] = std::numeric_limits<double>::denorm_min();
  }
  return frame;
}

// A frame of a case with soil: the water fields of make_frame and every soil field the engine
// writes (docs/output.md), with free_surface set for some soil particles.
FieldFrame make_soil_frame(std::size_t n, int dimensions, double time, std::uint64_t step,
                           unsigned seed) {
  FieldFrame frame = make_frame(n, dimensions, time, step, false, seed);
  std::mt19937_64 random(seed + 1000);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const struct {
    const char* name;
    const char* units;
    int components;
    double scale;
  } soil_fields[] = {{"numerical_density", "kg/m^3", 1, 2e3},
                     {"pore_pressure", "Pa", 1, -5e4},
                     {"saturation", "1", 1, 1.0},
                     {"porosity", "1", 1, 0.5},
                     {"plastic_strain", "1", 1, 1e-2},
                     {"seepage", "m/s", 3, 1e-5},
                     {"displacement", "m", 3, 0.1},
                     {"stress", "Pa", 6, -1e5},
                     {"effective_stress", "Pa", 6, -8e4}};
  for (const auto& s : soil_fields) {
    FieldFrame::RealField f{s.name, s.units, s.components, {}};
    for (std::size_t k = 0; k < n * s.components; ++k) f.values.push_back(s.scale * uniform(random));
    frame.fields.push_back(f);
  }
  for (std::size_t i = 0; i < n; ++i)
    frame.free_surface.push_back(frame.phase[i] == 1 && uniform(random) < 0.5 ? 1 : 0);
  if (n >= 3) frame.free_surface[1] = 1;  // phase[1] is soil: at least one particle on the surface
  return frame;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// ---------------------------------------------------------------------------------------------
// HDF5 reading

class H5Handle {
 public:
  H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~H5Handle() {
    if (id_ >= 0) close_(id_);
  }
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

struct H5File : H5Handle {
  explicit H5File(const fs::path& path)
      : H5Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose) {}
};

bool h5_exists(hid_t file, const std::string& path) {
  // Checks every link on the way, as H5Lexists needs.
  std::size_t position = 0;
  while ((position = path.find('/', position + 1)) != std::string::npos)
    if (H5Lexists(file, path.substr(0, position).c_str(), H5P_DEFAULT) <= 0) return false;
  return H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0;
}

std::vector<hsize_t> dataset_dims(hid_t file, const std::string& path) {
  H5Handle dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  H5Handle space(H5Dget_space(dataset), H5Sclose);
  std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(space));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

bool dataset_has_type(hid_t file, const std::string& path, hid_t expected) {
  H5Handle dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  H5Handle type(H5Dget_type(dataset), H5Tclose);
  return H5Tequal(type, expected) > 0;
}

template <typename T>
std::vector<T> read_dataset(hid_t file, const std::string& path, hid_t memory_type) {
  std::size_t count = 1;
  for (hsize_t d : dataset_dims(file, path)) count *= d;
  std::vector<T> values(count);
  H5Handle dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (count > 0) {
    EXPECT_GE(H5Dread(dataset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  }
  return values;
}

template <typename T>
T read_attribute(hid_t object, const char* name, hid_t memory_type) {
  T value{};
  H5Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  EXPECT_TRUE(attribute.valid()) << name;
  if (attribute.valid()) H5Aread(attribute, memory_type, &value);
  return value;
}

std::string read_string_attribute(hid_t file, const std::string& object_path, const char* name) {
  H5Handle object(H5Oopen(file, object_path.c_str(), H5P_DEFAULT), H5Oclose);
  H5Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  if (!attribute.valid()) return "<missing>";
  H5Handle file_type(H5Aget_type(attribute), H5Tclose);
  EXPECT_GT(H5Tis_variable_str(file_type), 0) << name;
  H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  char* text = nullptr;
  if (H5Aread(attribute, type, &text) < 0 || !text) return "<unreadable>";
  std::string result = text;
  H5free_memory(text);
  return result;
}

std::vector<std::string> group_members(hid_t file, const std::string& path) {
  H5Handle group(H5Gopen2(file, path.c_str(), H5P_DEFAULT), H5Gclose);
  H5G_info_t info{};
  H5Gget_info(group, &info);
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[256] = {};
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT);
    names.push_back(name);
  }
  return names;
}

// Compares one frame group of fields.h5 with the frame written into it.
void expect_frame_in_file(hid_t file, std::size_t index, const FieldFrame& frame,
                          const std::set<std::string>& written_fields) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "/frames/%06zu", index);
  const std::string group_path = buffer;
  SCOPED_TRACE(group_path);
  ASSERT_TRUE(h5_exists(file, group_path));
  const hsize_t n = frame.size();

  H5Handle group(H5Gopen2(file, group_path.c_str(), H5P_DEFAULT), H5Gclose);
  const double time = read_attribute<double>(group, "time", H5T_NATIVE_DOUBLE);
  EXPECT_EQ(std::memcmp(&time, &frame.time, sizeof time), 0) << time << " vs " << frame.time;
  EXPECT_EQ(read_attribute<std::uint64_t>(group, "step", H5T_NATIVE_UINT64), frame.step);

  std::set<std::string> expected_members = {"position", "phase", "id"};
  expected_members.insert(written_fields.begin(), written_fields.end());
  const std::vector<std::string> members = group_members(file, group_path);
  EXPECT_EQ(std::set<std::string>(members.begin(), members.end()), expected_members);

  const std::string position = group_path + "/position";
  EXPECT_EQ(dataset_dims(file, position), (std::vector<hsize_t>{n, 3}));
  EXPECT_TRUE(dataset_has_type(file, position, H5T_IEEE_F64LE));
  EXPECT_TRUE(same_bits(read_dataset<double>(file, position, H5T_NATIVE_DOUBLE), frame.position));
  EXPECT_EQ(read_string_attribute(file, position, "units"), "m");

  const std::string phase = group_path + "/phase";
  EXPECT_EQ(dataset_dims(file, phase), (std::vector<hsize_t>{n}));
  EXPECT_TRUE(dataset_has_type(file, phase, H5T_STD_U8LE));
  EXPECT_TRUE(same_bits(read_dataset<std::uint8_t>(file, phase, H5T_NATIVE_UINT8), frame.phase));

  const std::string id = group_path + "/id";
  EXPECT_EQ(dataset_dims(file, id), (std::vector<hsize_t>{n}));
  EXPECT_TRUE(dataset_has_type(file, id, H5T_STD_U32LE));
  EXPECT_TRUE(same_bits(read_dataset<std::uint32_t>(file, id, H5T_NATIVE_UINT32), frame.id));

  if (written_fields.count("free_surface")) {
    const std::string free_surface = group_path + "/free_surface";
    ASSERT_TRUE(h5_exists(file, free_surface));
    EXPECT_EQ(dataset_dims(file, free_surface), (std::vector<hsize_t>{n}));
    EXPECT_TRUE(dataset_has_type(file, free_surface, H5T_STD_U8LE));
    EXPECT_TRUE(same_bits(read_dataset<std::uint8_t>(file, free_surface, H5T_NATIVE_UINT8),
                          frame.free_surface));
    EXPECT_EQ(read_string_attribute(file, free_surface, "units"), "1");
  }

  for (const FieldFrame::RealField& f : frame.fields) {
    if (!written_fields.count(f.name)) continue;
    const std::string path = group_path + "/" + f.name;
    SCOPED_TRACE(path);
    ASSERT_TRUE(h5_exists(file, path));
    const std::vector<hsize_t> dims = f.components == 1
                                          ? std::vector<hsize_t>{n}
                                          : std::vector<hsize_t>{n, hsize_t(f.components)};
    EXPECT_EQ(dataset_dims(file, path), dims);
    EXPECT_TRUE(dataset_has_type(file, path, H5T_IEEE_F64LE));
    EXPECT_TRUE(same_bits(read_dataset<double>(file, path, H5T_NATIVE_DOUBLE), f.values));
    EXPECT_EQ(read_string_attribute(file, path, "units"), f.units);
  }
}

// The named datasets a frame gives with no fields filter: its RealFields and free_surface.
std::set<std::string> field_names(const FieldFrame& frame) {
  std::set<std::string> names;
  for (const auto& f : frame.fields) names.insert(f.name);
  if (!frame.free_surface.empty()) names.insert("free_surface");
  return names;
}

// ---------------------------------------------------------------------------------------------
// fields.h5

TEST(Hdf5FieldWriter, FramesReadBackBitExact) {
  const fs::path dir = fresh_directory();
  std::vector<FieldFrame> frames = {make_frame(37, 3, 0.0, 0, true, 1),
                                    make_frame(37, 3, 0.0125, 250, true, 2),
                                    make_frame(37, 3, 1.0 / 3.0, 1ull << 40, true, 3)};
  {
    Hdf5FieldWriter writer(dir / "fields.h5");
    for (const FieldFrame& frame : frames) writer.write(frame);
    EXPECT_EQ(writer.frames_written(), 3u);
    writer.close();
  }
  H5File file(dir / "fields.h5");
  ASSERT_TRUE(file.valid());
  EXPECT_EQ(read_string_attribute(file, "/", "format"), "cascade-fields-1");
  EXPECT_EQ(read_attribute<int>(file, "dimensions", H5T_NATIVE_INT), 3);
  EXPECT_EQ(group_members(file, "/frames"),
            (std::vector<std::string>{"000000", "000001", "000002"}));
  for (std::size_t i = 0; i < frames.size(); ++i)
    expect_frame_in_file(file, i, frames[i], field_names(frames[i]));
}

TEST(Hdf5FieldWriter, TwoDimensionalFramesKeepThreePositionComponents) {
  const fs::path dir = fresh_directory();
  const FieldFrame frame = make_frame(20, 2, 0.5, 10, false, 4);
  Hdf5FieldWriter(dir / "fields.h5").write(frame);  // the destructor closes the file
  H5File file(dir / "fields.h5");
  ASSERT_TRUE(file.valid());
  EXPECT_EQ(read_attribute<int>(file, "dimensions", H5T_NATIVE_INT), 2);
  expect_frame_in_file(file, 0, frame, field_names(frame));
  const std::vector<double> position =
      read_dataset<double>(file, "/frames/000000/position", H5T_NATIVE_DOUBLE);
  for (std::size_t i = 0; i < frame.size(); ++i) EXPECT_EQ(position[3 * i + 1], 0.0);
}

TEST(Hdf5FieldWriter, SoilFieldsReadBackBitExact) {
  const fs::path dir = fresh_directory();
  const std::vector<FieldFrame> frames = {make_soil_frame(31, 2, 0.0, 0, 21),
                                          make_soil_frame(29, 2, 0.5, 400, 22)};
  {
    Hdf5FieldWriter writer(dir / "fields.h5");
    for (const FieldFrame& frame : frames) writer.write(frame);
  }
  H5File file(dir / "fields.h5");
  ASSERT_TRUE(file.valid());
  EXPECT_EQ(read_attribute<int>(file, "dimensions", H5T_NATIVE_INT), 2);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::set<std::string> names = field_names(frames[i]);
    for (const char* soil : {"pore_pressure", "saturation", "porosity", "plastic_strain", "seepage",
                             "displacement", "stress", "effective_stress", "free_surface"})
      EXPECT_TRUE(names.count(soil)) << soil;  // the helper makes every field of the layout
    expect_frame_in_file(file, i, frames[i], names);
  }
  // Spot checks of the layout itself, independent of the helper above.
  EXPECT_EQ(dataset_dims(file, "/frames/000001/effective_stress"), (std::vector<hsize_t>{29, 6}));
  EXPECT_EQ(dataset_dims(file, "/frames/000001/seepage"), (std::vector<hsize_t>{29, 3}));
  EXPECT_EQ(dataset_dims(file, "/frames/000001/pore_pressure"), (std::vector<hsize_t>{29}));
  EXPECT_EQ(read_string_attribute(file, "/frames/000000/stress", "units"), "Pa");
  EXPECT_EQ(read_string_attribute(file, "/frames/000000/seepage", "units"), "m/s");
}

TEST(Hdf5FieldWriter, WaterOnlyFramesHaveNoFreeSurface) {
  const fs::path dir = fresh_directory();
  const FieldFrame frame = make_frame(8, 2, 0.0, 0, false, 23);
  ASSERT_TRUE(frame.free_surface.empty());
  Hdf5FieldWriter(dir / "fields.h5").write(frame);
  H5File file(dir / "fields.h5");
  ASSERT_TRUE(file.valid());
  EXPECT_FALSE(h5_exists(file, "/frames/000000/free_surface"));
  expect_frame_in_file(file, 0, frame, {"velocity", "pressure", "density"});
}

bool is_chunked_with_deflate(hid_t file, const std::string& path) {
  H5Handle dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  H5Handle properties(H5Dget_create_plist(dataset), H5Pclose);
  if (H5Pget_layout(properties) != H5D_CHUNKED) return false;
  for (int i = 0; i < H5Pget_nfilters(properties); ++i) {
    unsigned flags = 0;
    std::size_t count = 0;
    unsigned config = 0;
    if (H5Pget_filter2(properties, i, &flags, &count, nullptr, 0, nullptr, &config) ==
        H5Z_FILTER_DEFLATE)
      return true;
  }
  return false;
}

TEST(Hdf5FieldWriter, LargeFramesAreChunkedAndCompressed) {
  const fs::path dir = fresh_directory();
  const FieldFrame small = make_frame(100, 3, 0.0, 0, false, 5);
  const FieldFrame large = make_soil_frame(Hdf5FieldWriter::kCompressAbove + 904, 3, 1.0, 1, 6);
  {
    Hdf5FieldWriter writer(dir / "fields.h5");
    writer.write(small);
    writer.write(large);
  }
  H5File file(dir / "fields.h5");
  ASSERT_TRUE(file.valid());
  for (const char* name : {"position", "pressure", "stress", "phase", "id", "free_surface"})
    EXPECT_TRUE(is_chunked_with_deflate(file, std::string("/frames/000001/") + name)) << name;
  EXPECT_FALSE(is_chunked_with_deflate(file, "/frames/000000/position"));
  expect_frame_in_file(file, 0, small, field_names(small));
  expect_frame_in_file(file, 1, large, field_names(large));
}

TEST(Hdf5FieldWriter, FieldsFilterKeepsOnlyNamedFields) {
  const fs::path dir = fresh_directory();
  const FieldFrame frame = make_frame(10, 3, 0.0, 0, true, 7);
  Hdf5FieldWriter(dir / "fields.h5", {"pressure", "stress", "not_in_frame"}).write(frame);
  H5File file(dir / "fields.h5");
  ASSERT_TRUE(file.valid());
  expect_frame_in_file(file, 0, frame, {"pressure", "stress"});
}

TEST(Hdf5FieldWriter, FieldsFilterAppliesToFreeSurface) {
  const fs::path dir = fresh_directory();
  const FieldFrame frame = make_soil_frame(10, 3, 0.0, 0, 24);
  Hdf5FieldWriter(dir / "with.h5", {"pore_pressure", "free_surface"}).write(frame);
  Hdf5FieldWriter(dir / "without.h5", {"pore_pressure", "effective_stress"}).write(frame);
  H5File with(dir / "with.h5"), without(dir / "without.h5");
  ASSERT_TRUE(with.valid());
  ASSERT_TRUE(without.valid());
  expect_frame_in_file(with, 0, frame, {"pore_pressure", "free_surface"});
  expect_frame_in_file(without, 0, frame, {"pore_pressure", "effective_stress"});
}

TEST(Hdf5FieldWriter, ANewWriterRemovesAnEarlierRunsSidecar) {
  // The sidecar of a run of three frames in the same place named frames that the new, truncated
  // fields.h5 does not hold until its own first frame replaced it.
  const fs::path dir = fresh_directory();
  {
    Hdf5FieldWriter earlier(dir / "fields.h5");
    for (int k = 0; k < 3; ++k) earlier.write(make_frame(12, 3, 0.1 * k, std::uint64_t(k), false, 20 + k));
  }
  ASSERT_TRUE(fs::exists(dir / "fields.xdmf"));
  Hdf5FieldWriter writer(dir / "fields.h5");
  EXPECT_FALSE(fs::exists(dir / "fields.xdmf"));
  writer.write(make_frame(12, 3, 0.0, 0, false, 30));
  std::ifstream in(dir / "fields.xdmf");
  const std::string sidecar((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(sidecar.find("frame_000000"), std::string::npos);
  EXPECT_EQ(sidecar.find("frame_000001"), std::string::npos);
}

TEST(Hdf5FieldWriter, FlushedFramesReadableBeforeClose) {
  // A copy of the file taken while the writer is still open is what a killed run leaves behind.
  const fs::path dir = fresh_directory();
  const std::vector<FieldFrame> frames = {make_frame(12, 3, 0.0, 0, false, 8),
                                          make_frame(12, 3, 0.1, 5, false, 9)};
  Hdf5FieldWriter writer(dir / "fields.h5");
  for (const FieldFrame& frame : frames) writer.write(frame);
  fs::copy_file(dir / "fields.h5", dir / "snapshot.h5");
  {
    H5File file(dir / "snapshot.h5");
    ASSERT_TRUE(file.valid());
    EXPECT_EQ(group_members(file, "/frames").size(), 2u);
    for (std::size_t i = 0; i < frames.size(); ++i)
      expect_frame_in_file(file, i, frames[i], field_names(frames[i]));
  }
  writer.write(make_frame(12, 3, 0.2, 10, false, 10));
  writer.close();
}

TEST(Hdf5FieldWriter, RejectsInconsistentFramesAndWritesAfterClose) {
  const fs::path dir = fresh_directory();
  Hdf5FieldWriter writer(dir / "fields.h5");
  FieldFrame bad = make_frame(5, 3, 0.0, 0, false, 11);
  bad.fields[0].values.pop_back();
  EXPECT_THROW(writer.write(bad), std::invalid_argument);
  FieldFrame reserved = make_frame(5, 3, 0.0, 0, false, 11);
  reserved.fields[1].name = "position";
  EXPECT_THROW(writer.write(reserved), std::invalid_argument);
  FieldFrame twice = make_frame(5, 3, 0.0, 0, false, 11);
  twice.fields[2].name = "pressure";
  EXPECT_THROW(writer.write(twice), std::invalid_argument);
  FieldFrame surface_clash = make_frame(5, 3, 0.0, 0, false, 11);
  surface_clash.fields[1].name = "free_surface";
  EXPECT_THROW(writer.write(surface_clash), std::invalid_argument);
  FieldFrame short_surface = make_soil_frame(5, 3, 0.0, 0, 11);
  short_surface.free_surface.pop_back();
  EXPECT_THROW(writer.write(short_surface), std::invalid_argument);
  EXPECT_EQ(writer.frames_written(), 0u);

  writer.write(make_frame(5, 3, 0.0, 0, false, 12));
  EXPECT_THROW(writer.write(make_frame(5, 2, 0.1, 1, false, 13)), std::invalid_argument);
  EXPECT_EQ(writer.frames_written(), 1u);
  writer.close();
  EXPECT_THROW(writer.write(make_frame(5, 3, 0.2, 2, false, 14)), std::logic_error);

  H5File file(dir / "fields.h5");
  ASSERT_TRUE(file.valid());
  EXPECT_EQ(group_members(file, "/frames"), (std::vector<std::string>{"000000"}));
}

// ---------------------------------------------------------------------------------------------
// fields.xdmf

using XmlElement = vtkSmartPointer<vtkXMLDataElement>;

XmlElement read_xml(const fs::path& path) {
  return XmlElement::Take(vtkXMLUtilities::ReadElementFromFile(path.c_str()));
}

std::vector<vtkXMLDataElement*> children(vtkXMLDataElement* element, const char* name) {
  std::vector<vtkXMLDataElement*> found;
  for (int i = 0; i < element->GetNumberOfNestedElements(); ++i)
    if (std::strcmp(element->GetNestedElement(i)->GetName(), name) == 0)
      found.push_back(element->GetNestedElement(i));
  return found;
}

std::string attribute(vtkXMLDataElement* element, const char* name) {
  const char* value = element->GetAttribute(name);
  return value ? value : "<missing>";
}

std::string trimmed(const char* text) {
  std::string s = text ? text : "";
  const auto first = s.find_first_not_of(" \t\r\n");
  const auto last = s.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? "" : s.substr(first, last - first + 1);
}

// Checks that a <DataItem> names an existing dataset of fields.h5 with its dimensions and type;
// returns the dataset path.
std::string expect_data_item_matches(hid_t file, vtkXMLDataElement* item) {
  EXPECT_EQ(attribute(item, "Format"), "HDF");
  const std::string reference = trimmed(item->GetCharacterData());
  const std::string prefix = "fields.h5:";
  EXPECT_EQ(reference.substr(0, prefix.size()), prefix) << reference;
  const std::string path = reference.substr(prefix.size());
  EXPECT_TRUE(h5_exists(file, path)) << path;
  if (!h5_exists(file, path)) return path;

  std::string dims;
  for (hsize_t d : dataset_dims(file, path)) dims += (dims.empty() ? "" : " ") + std::to_string(d);
  EXPECT_EQ(attribute(item, "Dimensions"), dims) << path;

  H5Handle dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  H5Handle type(H5Dget_type(dataset), H5Tclose);
  EXPECT_EQ(attribute(item, "Precision"), std::to_string(H5Tget_size(type))) << path;
  const std::string number_type = attribute(item, "NumberType");
  if (H5Tget_class(type) == H5T_FLOAT) {
    EXPECT_EQ(number_type, "Float") << path;
  } else {
    EXPECT_EQ(H5Tget_sign(type), H5T_SGN_NONE) << path;
    EXPECT_EQ(number_type, H5Tget_size(type) == 1 ? "UChar" : "UInt") << path;
  }
  return path;
}

// The AttributeType each dataset of a frame must have in fields.xdmf (docs/output.md).
std::string expected_attribute_type(const FieldFrame& frame, const std::string& name) {
  const FieldFrame::RealField* f = frame.find(name);
  if (!f || f->components == 1) return "Scalar";  // also phase, id, free_surface
  if (f->components == 3) return "Vector";
  if (f->components == 9) return "Tensor";
  return "Matrix";  // six-component tensors too: XDMF's Tensor6 has another component order
}

// Writes the frames and checks fields.xdmf against them and against the fields.h5 it names.
void check_xdmf_sidecar(const fs::path& dir, const std::vector<FieldFrame>& frames) {
  {
    Hdf5FieldWriter writer(dir / "fields.h5");
    EXPECT_EQ(writer.xdmf_path(), dir / "fields.xdmf");
    for (const FieldFrame& frame : frames) writer.write(frame);
  }
  EXPECT_FALSE(fs::exists(dir / "fields.xdmf.tmp"));
  H5File file(dir / "fields.h5");
  ASSERT_TRUE(file.valid());

  const XmlElement root = read_xml(dir / "fields.xdmf");
  ASSERT_TRUE(root);
  EXPECT_STREQ(root->GetName(), "Xdmf");
  EXPECT_EQ(attribute(root, "Version"), "3.0");
  const auto domains = children(root, "Domain");
  ASSERT_EQ(domains.size(), 1u);
  const auto collections = children(domains[0], "Grid");
  ASSERT_EQ(collections.size(), 1u);
  EXPECT_EQ(attribute(collections[0], "GridType"), "Collection");
  EXPECT_EQ(attribute(collections[0], "CollectionType"), "Temporal");
  const auto grids = children(collections[0], "Grid");
  ASSERT_EQ(grids.size(), frames.size());

  for (std::size_t g = 0; g < grids.size(); ++g) {
    SCOPED_TRACE("grid " + std::to_string(g));
    const FieldFrame& frame = frames[g];
    const std::string n = std::to_string(frame.size());
    const auto times = children(grids[g], "Time");
    ASSERT_EQ(times.size(), 1u);
    EXPECT_EQ(std::strtod(attribute(times[0], "Value").c_str(), nullptr), frame.time);

    const auto topology = children(grids[g], "Topology");
    ASSERT_EQ(topology.size(), 1u);
    EXPECT_EQ(attribute(topology[0], "TopologyType"), "Polyvertex");
    EXPECT_EQ(attribute(topology[0], "NumberOfElements"), n);
    ASSERT_EQ(children(topology[0], "DataItem").size(), 1u);
    const std::string connectivity =
        expect_data_item_matches(file, children(topology[0], "DataItem")[0]);
    std::vector<std::uint32_t> expected(frame.size());
    for (std::size_t i = 0; i < expected.size(); ++i) expected[i] = static_cast<std::uint32_t>(i);
    EXPECT_EQ(read_dataset<std::uint32_t>(file, connectivity, H5T_NATIVE_UINT32), expected);

    const auto geometry = children(grids[g], "Geometry");
    ASSERT_EQ(geometry.size(), 1u);
    EXPECT_EQ(attribute(geometry[0], "GeometryType"), "XYZ");
    ASSERT_EQ(children(geometry[0], "DataItem").size(), 1u);
    const std::string position =
        expect_data_item_matches(file, children(geometry[0], "DataItem")[0]);
    EXPECT_TRUE(same_bits(read_dataset<double>(file, position, H5T_NATIVE_DOUBLE), frame.position));

    std::set<std::string> names;
    for (vtkXMLDataElement* a : children(grids[g], "Attribute")) {
      const std::string name = attribute(a, "Name");
      names.insert(name);
      EXPECT_EQ(attribute(a, "Center"), "Node");
      EXPECT_EQ(attribute(a, "AttributeType"), expected_attribute_type(frame, name)) << name;
      ASSERT_EQ(children(a, "DataItem").size(), 1u);
      const std::string path = expect_data_item_matches(file, children(a, "DataItem")[0]);
      char group[32];
      std::snprintf(group, sizeof group, "/frames/%06zu/", g);
      EXPECT_EQ(path, group + name);
    }
    std::set<std::string> expected_names = field_names(frame);
    expected_names.insert({"phase", "id"});
    EXPECT_EQ(names, expected_names);
  }
}

TEST(XdmfSidecar, ReferencesMatchHdf5Datasets) {
  const std::vector<FieldFrame> frames = {make_frame(9, 3, 0.0, 0, true, 15),
                                          make_frame(9, 3, 0.1, 7, true, 16),
                                          make_frame(14, 3, 1.0 / 7.0, 9, true, 17)};
  check_xdmf_sidecar(fresh_directory(), frames);
}

TEST(XdmfSidecar, SoilTensorsAreSixComponentMatricesAndFreeSurfaceUChar) {
  const fs::path dir = fresh_directory();
  const std::vector<FieldFrame> frames = {make_soil_frame(12, 2, 0.0, 0, 25),
                                          make_soil_frame(10, 2, 0.25, 50, 26)};
  check_xdmf_sidecar(dir, frames);

  // The same, spelled out for the last frame (10 particles).
  const XmlElement root = read_xml(dir / "fields.xdmf");
  ASSERT_TRUE(root);
  const auto grids = children(children(children(root, "Domain").at(0), "Grid").at(0), "Grid");
  ASSERT_EQ(grids.size(), 2u);
  struct Expected {
    const char* type;
    const char* dimensions;
    const char* number_type;
    const char* precision;
  };
  const std::map<std::string, Expected> expected = {
      {"stress", {"Matrix", "10 6", "Float", "8"}},
      {"effective_stress", {"Matrix", "10 6", "Float", "8"}},
      {"seepage", {"Vector", "10 3", "Float", "8"}},
      {"displacement", {"Vector", "10 3", "Float", "8"}},
      {"pore_pressure", {"Scalar", "10", "Float", "8"}},
      {"plastic_strain", {"Scalar", "10", "Float", "8"}},
      {"free_surface", {"Scalar", "10", "UChar", "1"}}};
  std::size_t found = 0;
  for (vtkXMLDataElement* a : children(grids[1], "Attribute")) {
    const auto e = expected.find(attribute(a, "Name"));
    if (e == expected.end()) continue;
    ++found;
    SCOPED_TRACE(e->first);
    EXPECT_EQ(attribute(a, "AttributeType"), e->second.type);
    vtkXMLDataElement* item = children(a, "DataItem").at(0);
    EXPECT_EQ(attribute(item, "Dimensions"), e->second.dimensions);
    EXPECT_EQ(attribute(item, "NumberType"), e->second.number_type);
    EXPECT_EQ(attribute(item, "Precision"), e->second.precision);
    EXPECT_EQ(trimmed(item->GetCharacterData()), "fields.h5:/frames/000001/" + e->first);
  }
  EXPECT_EQ(found, expected.size());
}

// ---------------------------------------------------------------------------------------------
// frame_NNNNNN.vtp and frames.pvd

void expect_vtp_matches(const fs::path& path, const FieldFrame& frame) {
  SCOPED_TRACE(path.string());
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* polydata = reader->GetOutput();
  ASSERT_EQ(polydata->GetNumberOfPoints(), static_cast<vtkIdType>(frame.size()));
  EXPECT_EQ(polydata->GetNumberOfVerts(), static_cast<vtkIdType>(frame.size()));
  EXPECT_EQ(polydata->GetVerts()->GetNumberOfConnectivityIds(),
            static_cast<vtkIdType>(frame.size()));

  auto* points = vtkDoubleArray::SafeDownCast(polydata->GetPoints()->GetData());
  ASSERT_NE(points, nullptr);
  EXPECT_TRUE(same_bits(
      std::vector<double>(points->GetPointer(0), points->GetPointer(0) + 3 * frame.size()),
      frame.position));

  vtkPointData* data = polydata->GetPointData();
  auto* phase = vtkUnsignedCharArray::SafeDownCast(data->GetAbstractArray("phase"));
  ASSERT_NE(phase, nullptr);
  EXPECT_TRUE(same_bits(
      std::vector<std::uint8_t>(phase->GetPointer(0), phase->GetPointer(0) + frame.size()),
      frame.phase));
  auto* id = vtkUnsignedIntArray::SafeDownCast(data->GetAbstractArray("id"));
  ASSERT_NE(id, nullptr);
  EXPECT_TRUE(same_bits(
      std::vector<std::uint32_t>(id->GetPointer(0), id->GetPointer(0) + frame.size()), frame.id));
  if (frame.free_surface.empty()) {
    EXPECT_EQ(data->GetAbstractArray("free_surface"), nullptr);
  } else {
    auto* free_surface = vtkUnsignedCharArray::SafeDownCast(data->GetAbstractArray("free_surface"));
    ASSERT_NE(free_surface, nullptr);
    EXPECT_EQ(free_surface->GetNumberOfComponents(), 1);
    EXPECT_TRUE(same_bits(std::vector<std::uint8_t>(free_surface->GetPointer(0),
                                                    free_surface->GetPointer(0) + frame.size()),
                          frame.free_surface));
  }
  EXPECT_EQ(data->GetNumberOfArrays(),
            static_cast<int>(2 + frame.fields.size() + !frame.free_surface.empty()));
  for (const FieldFrame::RealField& f : frame.fields) {
    auto* array = vtkDoubleArray::SafeDownCast(data->GetAbstractArray(f.name.c_str()));
    ASSERT_NE(array, nullptr) << f.name;
    EXPECT_EQ(array->GetNumberOfComponents(), f.components) << f.name;
    EXPECT_TRUE(
        same_bits(std::vector<double>(array->GetPointer(0), array->GetPointer(0) + f.values.size()),
                  f.values))
        << f.name;
    if (f.components == 6) {
      const char* const voigt[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};  // FieldFrame's order
      for (int c = 0; c < 6; ++c) {
        ASSERT_NE(array->GetComponentName(c), nullptr) << f.name << " " << c;
        EXPECT_STREQ(array->GetComponentName(c), voigt[c]) << f.name;
      }
    }
  }
  auto* time =
      vtkDoubleArray::SafeDownCast(polydata->GetFieldData()->GetAbstractArray("TimeValue"));
  ASSERT_NE(time, nullptr);
  EXPECT_EQ(time->GetValue(0), frame.time);
}

void check_vtk_series(const fs::path& dir, VtkWriterOptions options) {
  const std::vector<FieldFrame> frames = {make_frame(11, 3, 0.0, 0, true, 18),
                                          make_frame(11, 3, 0.25, 3, true, 19),
                                          make_frame(6, 2, 1.0 / 3.0, 4, false, 20),
                                          make_soil_frame(13, 2, 0.5, 8, 27)};
  VtkSeriesWriter writer(dir / "vtk", options);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const fs::path written = writer.write(frames[i]);
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06zu.vtp", i);
    EXPECT_EQ(written, dir / "vtk" / name);
    expect_vtp_matches(written, frames[i]);
  }
  EXPECT_EQ(writer.frames_written(), frames.size());
  EXPECT_FALSE(fs::exists(dir / "vtk" / "frames.pvd.tmp"));

  const XmlElement root = read_xml(writer.pvd_path());
  ASSERT_TRUE(root);
  EXPECT_EQ(attribute(root, "type"), "Collection");
  const auto collections = children(root, "Collection");
  ASSERT_EQ(collections.size(), 1u);
  const auto datasets = children(collections[0], "DataSet");
  ASSERT_EQ(datasets.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(std::strtod(attribute(datasets[i], "timestep").c_str(), nullptr), frames[i].time);
    const fs::path file = dir / "vtk" / attribute(datasets[i], "file");
    EXPECT_TRUE(fs::exists(file)) << file;
    expect_vtp_matches(file, frames[i]);
  }
}

TEST(VtkSeriesWriter, FramesReadBackWithXmlReader) { check_vtk_series(fresh_directory(), {}); }

TEST(VtkSeriesWriter, CompressedFramesReadBack) {
  check_vtk_series(fresh_directory(), VtkWriterOptions{true});
}

TEST(VtkSeriesWriter, RejectsFreeSurfaceOfWrongSize) {
  VtkSeriesWriter writer(fresh_directory() / "vtk");
  FieldFrame frame = make_soil_frame(7, 2, 0.0, 0, 28);
  frame.free_surface.push_back(0);
  EXPECT_THROW(writer.write(frame), std::invalid_argument);
  EXPECT_EQ(writer.frames_written(), 0u);
}

// ---------------------------------------------------------------------------------------------
// probes.csv

std::vector<std::string> split_lines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(ProbeCsvWriter, HeaderAndRowsParseBack) {
  const fs::path dir = fresh_directory();
  const std::vector<std::vector<double>> rows = {
      {1.0 / 3.0, std::numeric_limits<double>::quiet_NaN(), -1e-300},
      {2.5e8, 0.1, -0.0},
  };
  const std::vector<double> times = {0.1, 1.0 / 7.0};
  ProbeCsvWriter writer(dir / "probes.csv", {"gauge_a", "pore,pressure", "say \"hi\""});
  EXPECT_THROW(writer.write_row(0.0, {1.0}), std::invalid_argument);
  for (std::size_t r = 0; r < rows.size(); ++r) writer.write_row(times[r], rows[r]);

  // Read while the writer is still open: every row must already be on disk.
  const std::vector<std::string> lines = split_lines(dir / "probes.csv");
  ASSERT_EQ(lines.size(), 1 + rows.size());
  EXPECT_EQ(lines[0], "time,gauge_a,\"pore,pressure\",\"say \"\"hi\"\"\"");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::vector<double> parsed;
    std::stringstream line(lines[r + 1]);
    for (std::string cell; std::getline(line, cell, ',');) {
      char* end = nullptr;
      parsed.push_back(std::strtod(cell.c_str(), &end));
      EXPECT_EQ(*end, '\0') << cell;
    }
    ASSERT_EQ(parsed.size(), 1 + rows[r].size());
    EXPECT_EQ(parsed[0], times[r]);
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      if (std::isnan(rows[r][c])) {
        EXPECT_TRUE(std::isnan(parsed[c + 1]));
      } else {
        EXPECT_EQ(std::memcmp(&parsed[c + 1], &rows[r][c], sizeof(double)), 0) << lines[r + 1];
      }
    }
  }
  EXPECT_NE(lines[1].find(",nan,"), std::string::npos) << lines[1];
  writer.close();
  EXPECT_THROW(writer.write_row(1.0, {1.0, 2.0, 3.0}), std::logic_error);
}

// ---------------------------------------------------------------------------------------------
// run.json

// A strict JSON parser, enough to prove run.json is valid JSON and to read values back.
struct Json {
  enum class Kind { null, boolean, number, string, array, object } kind = Kind::null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Json> items;        // array elements or object values
  std::vector<std::string> keys;  // object keys, parallel to items

  bool has(const std::string& key) const {
    for (const auto& k : keys)
      if (k == key) return true;
    return false;
  }
  const Json& operator[](const std::string& key) const {
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i] == key) return items[i];
    throw std::runtime_error("no key " + key);
  }
};

class JsonParser {
 public:
  explicit JsonParser(std::string text) : text_(std::move(text)) {}

  Json document() {
    Json v = value();
    space();
    if (at_ != text_.size()) fail("trailing text");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(at_));
  }
  void space() {
    while (at_ < text_.size() && std::strchr(" \t\r\n", text_[at_])) ++at_;
  }
  char next() {
    if (at_ >= text_.size()) fail("unexpected end");
    return text_[at_++];
  }
  void expect(char c) {
    space();
    if (next() != c) fail(std::string("expected ") + c);
  }
  void literal(const char* word) {
    if (text_.compare(at_, std::strlen(word), word) != 0) fail("bad literal");
    at_ += std::strlen(word);
  }

  Json value() {
    space();
    Json v;
    if (at_ >= text_.size()) fail("unexpected end");
    const char c = text_[at_];
    if (c == '{') {
      v.kind = Json::Kind::object;
      ++at_;
      space();
      if (text_[at_] == '}') return ++at_, v;
      do {
        space();
        v.keys.push_back(string());
        expect(':');
        v.items.push_back(value());
        space();
      } while (text_[at_] == ',' && ++at_);
      expect('}');
    } else if (c == '[') {
      v.kind = Json::Kind::array;
      ++at_;
      space();
      if (text_[at_] == ']') return ++at_, v;
      do v.items.push_back(value()), space();
      while (text_[at_] == ',' && ++at_);
      expect(']');
    } else if (c == '"') {
      v.kind = Json::Kind::string;
      v.string = string();
    } else if (c == 't' || c == 'f') {
      v.kind = Json::Kind::boolean;
      v.boolean = c == 't';
      literal(v.boolean ? "true" : "false");
    } else if (c == 'n') {
      literal("null");
    } else {
      const std::size_t start = at_;
      while (at_ < text_.size() && std::strchr("+-0123456789.eE", text_[at_])) ++at_;
      if (start == at_) fail("unexpected character");
      v.kind = Json::Kind::number;
      v.number = std::strtod(text_.substr(start, at_ - start).c_str(), nullptr);
    }
    return v;
  }

  std::string string() {
    if (next() != '"') fail("expected string");
    std::string s;
    for (;;) {
      const char c = next();
      if (c == '"') return s;
      if (static_cast<unsigned char>(c) < 0x20) fail("raw control character");
      if (c != '\\') {
        s += c;
        continue;
      }
      const char e = next();
      switch (e) {
        case '"':
        case '\\':
        case '/':
          s += e;
          break;
        case 'b':
          s += '\b';
          break;
        case 'f':
          s += '\f';
          break;
        case 'n':
          s += '\n';
          break;
        case 'r':
          s += '\r';
          break;
        case 't':
          s += '\t';
          break;
        case 'u': {
          if (at_ + 4 > text_.size()) fail("short \\u escape");
          const unsigned code = std::stoul(text_.substr(at_, 4), nullptr, 16);
          at_ += 4;
          if (code < 0x80) {
            s += static_cast<char>(code);
          } else if (code < 0x800) {
            s += static_cast<char>(0xc0 | (code >> 6));
            s += static_cast<char>(0x80 | (code & 0x3f));
          } else {
            s += static_cast<char>(0xe0 | (code >> 12));
            s += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
            s += static_cast<char>(0x80 | (code & 0x3f));
          }
          break;
        }
        default:
          fail("bad escape");
      }
    }
  }

  std::string text_;
  std::size_t at_ = 0;
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(RunSummary, FailedRunHasEveryKeyAndEscapedError) {
  const fs::path dir = fresh_directory();
  RunSummary summary;
  summary.case_name = "slope \"B\"";
  summary.status = RunSummary::Status::failed;
  summary.error = "solver diverged: \"pressure\" at C:\\tmp\nnext\tline\x01 bad byte \xff é";
  summary.precision = "float";
  summary.sim_time = 1.0 / 3.0;
  summary.steps = 123456789012ull;
  summary.wall_seconds = 12.5;
  summary.particles = {1000, 600, 300, 100};
  summary.particle_steps_per_second = 9.87654321e7;
  summary.bytes_per_particle = 412.0;
  summary.lost_particles = 3;
  summary.pore_water = {true, 0.52, -0.125, -0.031};
  summary.events = {{0.5, 100, "steer", "rainfall 20 -> 40 mm/h"},
                    {0.75, 150, "particles_lost", "3 left the \"domain\""}};
  write_run_json(dir / "run.json", summary);
  EXPECT_FALSE(fs::exists(dir / "run.json.tmp"));

  const std::string text = read_text(dir / "run.json");
  EXPECT_NE(text.find(R"(solver diverged: \"pressure\" at C:\\tmp\nnext\tline)"), std::string::npos)
      << text;
  const Json json = JsonParser(text).document();
  ASSERT_EQ(json.kind, Json::Kind::object);
  for (const char* key : {"status", "error", "sim_time", "steps", "wall_seconds", "particles",
                          "particle_steps_per_second", "bytes_per_particle", "events", "case",
                          "precision", "lost_particles"})
    EXPECT_TRUE(json.has(key)) << key;
  EXPECT_EQ(json["status"].string, "failed");
  EXPECT_EQ(json["error"].string,
            "solver diverged: \"pressure\" at C:\\tmp\nnext\tline\x01 bad byte \xef\xbf\xbd é");
  EXPECT_EQ(json["case"].string, summary.case_name);
  EXPECT_EQ(json["precision"].string, "float");
  EXPECT_EQ(json["sim_time"].number, summary.sim_time);
  EXPECT_EQ(json["steps"].number, 123456789012.0);
  EXPECT_EQ(json["wall_seconds"].number, 12.5);
  EXPECT_EQ(json["particles"]["total"].number, 1000);
  EXPECT_EQ(json["particles"]["water"].number, 600);
  EXPECT_EQ(json["particles"]["soil"].number, 300);
  EXPECT_EQ(json["particles"]["boundary"].number, 100);
  EXPECT_EQ(json["particle_steps_per_second"].number, 9.87654321e7);
  EXPECT_EQ(json["bytes_per_particle"].number, 412.0);
  EXPECT_EQ(json["lost_particles"].number, 3);
  EXPECT_EQ(json["pore_water"]["rain"].number, 0.52);
  EXPECT_EQ(json["pore_water"]["walls"].number, -0.125);
  EXPECT_EQ(json["pore_water"]["surface"].number, -0.031);
  ASSERT_EQ(json["events"].items.size(), 2u);
  EXPECT_EQ(json["events"].items[1]["time"].number, 0.75);
  EXPECT_EQ(json["events"].items[1]["step"].number, 150);
  EXPECT_EQ(json["events"].items[1]["kind"].string, "particles_lost");
  EXPECT_EQ(json["events"].items[1]["detail"].string, "3 left the \"domain\"");
}

TEST(RunSummary, CompletedRunHasNoErrorAndNullForNonFinite) {
  const fs::path dir = fresh_directory();
  RunSummary summary;
  summary.case_name = "column";
  summary.error = "ignored when completed";
  summary.wall_seconds = 0.0;
  summary.particle_steps_per_second = std::numeric_limits<double>::infinity();
  write_run_json(dir / "run.json", summary);
  const Json json = JsonParser(read_text(dir / "run.json")).document();
  EXPECT_EQ(json["status"].string, "completed");
  EXPECT_FALSE(json.has("error"));
  EXPECT_EQ(json["particle_steps_per_second"].kind, Json::Kind::null);
  EXPECT_EQ(json["events"].kind, Json::Kind::array);
  EXPECT_TRUE(json["events"].items.empty());
  EXPECT_FALSE(json.has("pore_water"));  // a case without soil
}

}  // namespace
}  // namespace cascade
