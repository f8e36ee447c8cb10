#include "server/io/checkpoint_file.h"

#include <cstdint>
#include <vector>

#include "server/io/hdf5_support.h"

namespace cascade {
namespace {

using namespace hdf5;

constexpr char kFormat[] = "cascade-checkpoint-1";

template <typename T>
void write_array(hid_t group, const char* name, hid_t file_type, hid_t memory_type, const std::vector<T>& values) {
  const hsize_t size = values.size();
  Handle space(H5Screate_simple(1, &size, nullptr), H5Sclose, std::string("create space of ") + name);
  Handle dataset(H5Dcreate2(group, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
                 std::string("create dataset ") + name);
  if (size > 0) check(H5Dwrite(dataset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), std::string("write ") + name);
}

void write_bytes(hid_t group, const char* name, const std::string& bytes) {
  write_array(group, name, H5T_NATIVE_UINT8, H5T_NATIVE_UINT8, std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
}

void write_double(hid_t object, const char* name, double v) {
  write_scalar_attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &v);
}
void write_u64(hid_t object, const char* name, std::uint64_t v) {
  write_scalar_attribute(object, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &v);
}

template <typename T>
std::vector<T> read_array(hid_t group, const std::string& name, hid_t memory_type) {
  Handle dataset(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  Handle space(H5Dget_space(dataset), H5Sclose, "get space of " + name);
  std::vector<T> values(std::size_t(H5Sget_simple_extent_npoints(space)));
  if (!values.empty()) check(H5Dread(dataset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "read " + name);
  return values;
}

std::string read_bytes(hid_t group, const char* name) {
  const auto bytes = read_array<std::uint8_t>(group, name, H5T_NATIVE_UINT8);
  return {bytes.begin(), bytes.end()};
}

template <typename T>
T read_scalar(hid_t object, const char* name, hid_t memory_type) {
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose, std::string("open attribute ") + name);
  T v{};
  check(H5Aread(attribute, memory_type, &v), std::string("read attribute ") + name);
  return v;
}
double read_double(hid_t object, const char* name) { return read_scalar<double>(object, name, H5T_NATIVE_DOUBLE); }
std::uint64_t read_u64(hid_t object, const char* name) { return read_scalar<std::uint64_t>(object, name, H5T_NATIVE_UINT64); }

std::string read_string(hid_t object, const char* name) {
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose, std::string("open attribute ") + name);
  Handle type(H5Aget_type(attribute), H5Tclose, std::string("get type of ") + name);
  char* text = nullptr;
  check(H5Aread(attribute, type, &text), std::string("read attribute ") + name);
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

void write_forcing(hid_t file, const HydraulicForcing& f) {
  Handle group(H5Gcreate2(file, "forcing", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create /forcing");
  write_double(group, "rainfall_intensity", f.rainfall_intensity);
  write_double(group, "ponding_pressure", f.ponding_pressure);
  write_double(group, "drying_pressure", f.drying_pressure);
  write_u64(group, "has_surface_pressure", f.has_surface_pressure);
  write_double(group, "surface_pressure", f.surface_pressure);
  write_u64(group, "has_region", f.has_region);
  write_array(group, "region_min", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, std::vector<double>(f.region_min.begin(), f.region_min.end()));
  write_array(group, "region_max", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, std::vector<double>(f.region_max.begin(), f.region_max.end()));
}

HydraulicForcing read_forcing(hid_t file) {
  Handle group(H5Gopen2(file, "forcing", H5P_DEFAULT), H5Gclose, "open /forcing");
  HydraulicForcing f;
  f.rainfall_intensity = read_double(group, "rainfall_intensity");
  f.ponding_pressure = read_double(group, "ponding_pressure");
  f.drying_pressure = read_double(group, "drying_pressure");
  f.has_surface_pressure = read_u64(group, "has_surface_pressure") != 0;
  f.surface_pressure = read_double(group, "surface_pressure");
  f.has_region = read_u64(group, "has_region") != 0;
  const auto min = read_array<double>(group, "region_min", H5T_NATIVE_DOUBLE);
  const auto max = read_array<double>(group, "region_max", H5T_NATIVE_DOUBLE);
  if (min.size() != 3 || max.size() != 3) throw std::runtime_error("/forcing/region_min and region_max need 3 values");
  for (int a = 0; a < 3; ++a) f.region_min[a] = min[a], f.region_max[a] = max[a];
  return f;
}

// The names of a group's members.
std::vector<std::string> dataset_names(hid_t group) {
  H5G_info_t info;
  check(H5Gget_info(group, &info), "list a group");
  std::vector<std::string> names;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    char name[256];
    if (H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name, H5P_DEFAULT) < 0)
      throw std::runtime_error("cannot list a group");
    names.emplace_back(name);
  }
  return names;
}

// FNV-1a (64 bit) over the checkpoint's content, in the order written: a file damaged after it
// was written (flipped bytes in its datasets restored without an error, issue 14) no longer
// matches the root's `checksum` attribute.
class Digest {
 public:
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) hash_ = (hash_ ^ p[k]) * 1099511628211ull;
  }
  void add(const std::string& s) { add(std::uint64_t(s.size())), add(s.data(), s.size()); }
  template <typename T>
  void add(const std::vector<T>& v) { add(std::uint64_t(v.size())), add(v.data(), v.size() * sizeof(T)); }
  void add(double v) { add(&v, sizeof v); }
  void add(std::uint64_t v) { add(&v, sizeof v); }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;
};

std::uint64_t content_checksum(const Checkpoint& c, const std::string& spec_bytes) {
  Digest d;
  d.add(c.simulation), d.add(spec_bytes), d.add(c.journal), d.add(c.wall_time);
  const EngineState& s = c.engine;
  d.add(s.time), d.add(s.steps), d.add(s.last_dt), d.add(std::uint64_t(s.dimensions));
  d.add(std::uint64_t(s.single_precision)), d.add(std::uint64_t(s.particles));
  const HydraulicForcing& f = s.forcing;
  d.add(f.rainfall_intensity), d.add(f.ponding_pressure), d.add(f.drying_pressure);
  d.add(std::uint64_t(f.has_surface_pressure)), d.add(f.surface_pressure), d.add(std::uint64_t(f.has_region));
  for (int a = 0; a < 3; ++a) d.add(double(f.region_min[a])), d.add(double(f.region_max[a]));
  d.add(s.displacement_reference);
  for (const auto& [name, values] : s.reals) d.add(name), d.add(values);
  for (const auto& [name, values] : s.integers) d.add(name), d.add(values);
  d.add(std::uint64_t(s.stage));
  for (const auto& [name, value] : s.stage_values) d.add(name), d.add(value);
  // The pore-water account (2026-12-06); a zero one hashes as files from before it did.
  const PoreWaterAccount& w = s.pore_water;
  if (w.rain != 0 || w.walls != 0 || w.surface != 0) d.add(w.rain), d.add(w.walls), d.add(w.surface);
  return d.value();
}

// The root's attributes, which a listing reads alone.
void write_summary(hid_t file, const Checkpoint& c) {
  write_string_attribute(file, "format", kFormat);
  write_string_attribute(file, "simulation", c.simulation);
  write_string_attribute(file, "case_name", c.spec.name());
  write_double(file, "wall_time", c.wall_time);
  write_double(file, "time", c.engine.time);
  write_u64(file, "step", c.engine.steps);
  write_double(file, "last_dt", c.engine.last_dt);
  write_u64(file, "dimensions", std::uint64_t(c.engine.dimensions));
  write_string_attribute(file, "precision", c.engine.single_precision ? "float" : "double");
  write_u64(file, "particles", c.engine.particles);
}

CheckpointSummary read_summary(hid_t file) {
  if (read_string(file, "format") != kFormat) throw std::runtime_error(std::string("not a ") + kFormat + " file");
  CheckpointSummary s;
  s.simulation = read_string(file, "simulation");
  s.case_name = read_string(file, "case_name");
  s.wall_time = read_double(file, "wall_time");
  s.time = read_double(file, "time");
  s.step = read_u64(file, "step");
  s.particles = std::size_t(read_u64(file, "particles"));
  return s;
}

// Opens for reading; the errors name the file.
template <typename Read>
auto read_file(const std::filesystem::path& path, Read read) {
  try {
    Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open");
    return read(hid_t(file));
  } catch (const std::exception& e) {
    throw std::runtime_error("checkpoint " + path.string() + ": " + e.what());
  }
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const Checkpoint& c) {
  auto partial = path;
  partial += ".partial";
  try {
    {
      Handle file(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "create");
      write_summary(file, c);
      const std::string spec_bytes = c.spec.SerializeAsString();
      write_u64(file, "checksum", content_checksum(c, spec_bytes));
      // The pore water's account (EngineState::pore_water), as root attributes beside the time.
      write_double(file, "pore_water_rain", c.engine.pore_water.rain);
      write_double(file, "pore_water_walls", c.engine.pore_water.walls);
      write_double(file, "pore_water_surface", c.engine.pore_water.surface);
      write_bytes(file, "case_spec", spec_bytes);
      write_bytes(file, "journal", c.journal);
      write_forcing(file, c.engine.forcing);
      write_array(file, "displacement_reference", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, c.engine.displacement_reference);
      Handle engine(H5Gcreate2(file, "engine", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create /engine");
      for (const auto& [name, values] : c.engine.reals)
        write_array(engine, name.c_str(), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, values);
      for (const auto& [name, values] : c.engine.integers)
        write_array(engine, name.c_str(), H5T_STD_U32LE, H5T_NATIVE_UINT32, values);
      // The stage and the numbers it carries (EngineState::stage, stage_values).
      Handle stage(H5Gcreate2(file, "stage", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create /stage");
      write_u64(stage, "index", std::uint64_t(c.engine.stage));
      for (const auto& [name, value] : c.engine.stage_values)
        write_array(stage, name.c_str(), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, std::vector<double>{value});
      check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush");
    }
    std::filesystem::rename(partial, path);
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw std::runtime_error("checkpoint " + path.string() + ": " + e.what());
  }
}

CheckpointSummary read_checkpoint_summary(const std::filesystem::path& path) {
  return read_file(path, [](hid_t file) { return read_summary(file); });
}

Checkpoint read_checkpoint(const std::filesystem::path& path) {
  return read_file(path, [](hid_t file) {
    const CheckpointSummary summary = read_summary(file);
    Checkpoint c;
    c.simulation = summary.simulation;
    c.wall_time = summary.wall_time;
    const std::string spec_bytes = read_bytes(file, "case_spec");
    if (!c.spec.ParseFromString(spec_bytes)) throw std::runtime_error("case_spec is not a ScenarioSpec");
    c.journal = read_bytes(file, "journal");
    EngineState& s = c.engine;
    s.time = summary.time;
    s.steps = summary.step;
    s.particles = summary.particles;
    s.last_dt = read_double(file, "last_dt");
    s.dimensions = int(read_u64(file, "dimensions"));
    s.single_precision = read_string(file, "precision") == "float";
    s.forcing = read_forcing(file);
    s.displacement_reference = read_array<double>(file, "displacement_reference", H5T_NATIVE_DOUBLE);
    {
      Handle stage(H5Gopen2(file, "stage", H5P_DEFAULT), H5Gclose, "open /stage");
      s.stage = int(read_u64(stage, "index"));
      for (const std::string& name : dataset_names(stage)) {
        const auto value = read_array<double>(stage, name.c_str(), H5T_NATIVE_DOUBLE);
        if (value.size() != 1) throw std::runtime_error("/stage/" + name + " must hold one value");
        s.stage_values[name] = value[0];
      }
    }
    if (H5Aexists(file, "pore_water_rain") > 0) {  // files from before 2026-12-06 have none
      s.pore_water.rain = read_double(file, "pore_water_rain");
      s.pore_water.walls = read_double(file, "pore_water_walls");
      s.pore_water.surface = read_double(file, "pore_water_surface");
    }
    Handle engine(H5Gopen2(file, "engine", H5P_DEFAULT), H5Gclose, "open /engine");
    for (const std::string& name : dataset_names(engine)) {
      Handle dataset(H5Dopen2(engine, name.c_str(), H5P_DEFAULT), H5Dclose, "open /engine/" + name);
      Handle type(H5Dget_type(dataset), H5Tclose, "get type of /engine/" + name);
      if (H5Tget_class(type) == H5T_INTEGER)
        s.integers[name] = read_array<std::uint32_t>(engine, name.c_str(), H5T_NATIVE_UINT32);
      else s.reals[name] = read_array<double>(engine, name.c_str(), H5T_NATIVE_DOUBLE);
    }
    // Files written before the checksum (2026-12-02) have none and are taken as they are.
    if (H5Aexists(file, "checksum") > 0 && read_u64(file, "checksum") != content_checksum(c, spec_bytes))
      throw std::runtime_error("its content does not match its checksum: the file is damaged");
    return c;
  });
}

}  // namespace cascade
