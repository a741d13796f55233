#include "eqhb/output/hdf5_file.h"

#include <hdf5.h>

#include "eqhb/io_error.h"

namespace eqhb::output {

namespace {

// Owns one HDF5 handle, closed by `close` (H5Dclose, H5Sclose, ...).
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

// HDF5 prints a stack of its errors on stderr by default; ours are thrown.
void quietErrors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

hid_t stringType() {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  return type;
}

}  // namespace

Hdf5File::Hdf5File(const std::string& path) : path_(path) {
  quietErrors();
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file_ < 0) throwIoError(path, "cannot create the HDF5 file");
}

Hdf5File::~Hdf5File() {
  if (file_ >= 0) H5Fclose(file_);
}

void Hdf5File::group(const std::string& path) {
  Handle g{H5Gcreate2(file_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose};
  if (g.id < 0) throwIoError(path_, "cannot create the group " + path);
}

void Hdf5File::dataset(const std::string& path, long type, const void* data,
                       const std::vector<unsigned long long>& dims) {
  std::vector<hsize_t> sizes(dims.begin(), dims.end());
  Handle space{H5Screate_simple(static_cast<int>(sizes.size()), sizes.data(), nullptr), H5Sclose};
  Handle set{space.id < 0 ? -1
                          : H5Dcreate2(file_, path.c_str(), static_cast<hid_t>(type), space.id, H5P_DEFAULT,
                                       H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose};
  bool empty = false;
  for (hsize_t d : sizes) empty = empty || d == 0;
  if (set.id < 0 || (!empty && H5Dwrite(set.id, static_cast<hid_t>(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0))
    throwIoError(path_, "cannot write the dataset " + path);
}

void Hdf5File::doubles(const std::string& path, const std::vector<double>& values) {
  dataset(path, H5T_NATIVE_DOUBLE, values.data(), {values.size()});
}

void Hdf5File::matrix(const std::string& path, const std::vector<double>& values, std::size_t rows,
                      std::size_t cols) {
  dataset(path, H5T_NATIVE_DOUBLE, values.data(), {rows, cols});
}

void Hdf5File::array(const std::string& path, const std::vector<double>& values,
                     const std::vector<std::size_t>& dims) {
  dataset(path, H5T_NATIVE_DOUBLE, values.data(), std::vector<unsigned long long>(dims.begin(), dims.end()));
}

void Hdf5File::integers(const std::string& path, const std::vector<std::int64_t>& values) {
  dataset(path, H5T_NATIVE_INT64, values.data(), {values.size()});
}

void Hdf5File::strings(const std::string& path, const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  for (const std::string& s : values) pointers.push_back(s.c_str());
  Handle type{stringType(), H5Tclose};
  dataset(path, type.id, pointers.data(), {values.size()});
}

void Hdf5File::attribute(const std::string& path, const std::string& name, const std::string& value) {
  Handle type{stringType(), H5Tclose};
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle a{H5Acreate_by_name(file_, path.c_str(), name.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT,
                             H5P_DEFAULT),
           H5Aclose};
  const char* text = value.c_str();
  if (a.id < 0 || H5Awrite(a.id, type.id, &text) < 0)
    throwIoError(path_, "cannot write the attribute " + name + " of " + path);
}

void Hdf5File::attribute(const std::string& path, const std::string& name, double value) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle a{H5Acreate_by_name(file_, path.c_str(), name.c_str(), H5T_NATIVE_DOUBLE, space.id, H5P_DEFAULT,
                             H5P_DEFAULT, H5P_DEFAULT),
           H5Aclose};
  if (a.id < 0 || H5Awrite(a.id, H5T_NATIVE_DOUBLE, &value) < 0)
    throwIoError(path_, "cannot write the attribute " + name + " of " + path);
}

void Hdf5File::close() {
  const hid_t file = file_;
  file_ = -1;
  if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0 || H5Fclose(file) < 0) throwIoError(path_, "cannot complete the HDF5 file");
}

}  // namespace eqhb::output
