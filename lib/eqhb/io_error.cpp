#include "eqhb/io_error.h"

#include <cerrno>
#include <cstring>

namespace eqhb {

void throwIoError(const std::string& path, const std::string& what) {
  const int error = errno;
  throw IoError(path + ": " + what + (error ? " (" + std::string(std::strerror(error)) + ")" : ""));
}

}  // namespace eqhb
