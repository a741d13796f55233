// A results file in HDF5 (readable by h5py, MATLAB, HDFView): groups,
// datasets of doubles, integers and strings, attributes. A thin owner of the
// HDF5 C library's handles; each write throws IoError naming the file and
// the object, so a full disk or a bad path never leaves a silent half file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace eqhb::output {

class Hdf5File {
 public:
  // Creates `path` (an existing file is replaced).
  explicit Hdf5File(const std::string& path);
  ~Hdf5File();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  // Object paths are absolute ("/points/omega"); a group is made before
  // anything inside it.
  void group(const std::string& path);
  void doubles(const std::string& path, const std::vector<double>& values);
  // rows x cols, row-major (row i: values[i * cols .. (i + 1) * cols)).
  void matrix(const std::string& path, const std::vector<double>& values, std::size_t rows, std::size_t cols);
  // Of any rank, row-major (the last index fastest).
  void array(const std::string& path, const std::vector<double>& values, const std::vector<std::size_t>& dims);
  void integers(const std::string& path, const std::vector<std::int64_t>& values);
  void strings(const std::string& path, const std::vector<std::string>& values);
  // On the object at `path` ("/" for the file).
  void attribute(const std::string& path, const std::string& name, const std::string& value);
  void attribute(const std::string& path, const std::string& name, double value);
  // Flushes and closes; throws IoError if the file cannot be completed.
  void close();

 private:
  void dataset(const std::string& path, long type, const void* data, const std::vector<unsigned long long>& dims);
  std::string path_;
  long long file_ = -1;
};

}  // namespace eqhb::output
