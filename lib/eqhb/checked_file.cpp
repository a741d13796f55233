#include "eqhb/checked_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

#include "eqhb/error.h"
#include "eqhb/io_error.h"

namespace eqhb {

namespace {

// write(2) until all of `text` is out; a short write that makes no
// progress (ENOSPC) is an error.
void writeAll(int fd, const std::string& path, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;
      throwIoError(path, "cannot write (" + std::to_string(done) + " of " + std::to_string(text.size()) +
                             " bytes written)");
    }
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace

AppendOnlyFile::AppendOnlyFile(const std::string& path)
    : path_(path), fd_(::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644)),
      last_sync_(std::chrono::steady_clock::now()) {
  if (fd_ < 0) throwIoError(path, "cannot open for appending");
}

AppendOnlyFile::~AppendOnlyFile() { ::close(fd_); }

void AppendOnlyFile::append(const std::string& text) {
  writeAll(fd_, path_, text);
  if (std::chrono::steady_clock::now() - last_sync_ >= sync_interval) sync();
}

void AppendOnlyFile::sync() {
  if (::fdatasync(fd_) != 0) throwIoError(path_, "cannot sync to disk");
  last_sync_ = std::chrono::steady_clock::now();
}

void writeFileChecked(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throwIoError(temporary, "cannot create");
  try {
    writeAll(fd, temporary, text);
    if (::fsync(fd) != 0) throwIoError(temporary, "cannot sync to disk");
  } catch (const IoError&) {
    ::close(fd);
    ::unlink(temporary.c_str());
    throw;
  }
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    errno = error;
    throwIoError(temporary, "cannot close");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    errno = error;
    throwIoError(path, "cannot replace with " + temporary);
  }
}

}  // namespace eqhb
