#include "eqhb/studies/study_folder_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <string>

#include "eqhb/error.h"
#include "eqhb/io_error.h"

namespace eqhb {

namespace {

std::string readHolder(int fd) {
  char text[256] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string holder = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : std::string();
  while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\r')) holder.pop_back();
  return holder.empty() ? "a process that has not written its id yet" : holder;
}

}  // namespace

StudyFolderLock::StudyFolderLock(const std::string& dir) {
  const std::string path = dir + "/lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throwIoError(path, "cannot open the study folder's lock file");
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string holder = error == EWOULDBLOCK ? readHolder(fd_) : std::string();
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK)
      throwInputError("out", dir,
                      "is in use by another study (" + holder + " holds " + path +
                          "): wait for it to end, or give another folder");
    errno = error;
    throwIoError(path, "cannot lock the study folder");
  }
  char host[HOST_NAME_MAX + 1] = {};
  ::gethostname(host, sizeof host - 1);
  const std::string holder = "process " + std::to_string(::getpid()) + " on " + host + "\n";
  errno = ENOSPC;  // a short pwrite sets none
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, holder.data(), holder.size(), 0) != static_cast<ssize_t>(holder.size())) {
    const int error = errno;
    ::close(fd_);
    errno = error;
    throwIoError(path, "cannot write the lock holder");
  }
}

StudyFolderLock::~StudyFolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace eqhb
