// Error type for a file that could not be created or written (a full disk,
// a lost folder): not the input's fault, so the command line tells it apart
// from InputError (exit code 3 instead of 2). The message names the file
// and the system's reason.
#pragma once

#include <stdexcept>
#include <string>

namespace eqhb {

class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws IoError("PATH: WHAT (strerror(errno))"), errno as the failed call left it.
[[noreturn]] void throwIoError(const std::string& path, const std::string& what);

}  // namespace eqhb
