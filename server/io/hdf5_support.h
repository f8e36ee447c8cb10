// Small helpers of the HDF5 C API shared by the io/ files that write HDF5 (fields.h5,
// checkpoints). Included by .cpp files only: it needs HDF5's include path, which cascade_io keeps
// private.
#pragma once

#include <hdf5.h>

#include <stdexcept>
#include <string>

namespace cascade::hdf5 {

// Owns one HDF5 identifier; the constructor throws when the call that made it failed.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("HDF5: cannot " + what);
  }
  ~Handle() { close_(id_); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

inline void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: cannot " + what);
}

inline void write_string_attribute(hid_t object, const char* name, const std::string& value) {
  // Variable-length UTF-8: h5py returns it as str, C readers as char*.
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy string type");
  check(H5Tset_size(type, H5T_VARIABLE), "size string type");
  check(H5Tset_cset(type, H5T_CSET_UTF8), "set string encoding");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar space");
  Handle attribute(H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                   std::string("create attribute ") + name);
  const char* text = value.c_str();
  check(H5Awrite(attribute, type, &text), std::string("write attribute ") + name);
}

inline void write_scalar_attribute(hid_t object, const char* name, hid_t file_type, hid_t memory_type,
                            const void* value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar space");
  Handle attribute(H5Acreate2(object, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                   std::string("create attribute ") + name);
  check(H5Awrite(attribute, memory_type, value), std::string("write attribute ") + name);
}

}  // namespace cascade::hdf5
