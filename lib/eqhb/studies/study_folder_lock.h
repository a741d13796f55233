// One study at a time in a study folder: an exclusive flock(2) on DIR/lock,
// held for the life of the object (the kernel drops it when the process
// ends, however it ends, so a killed study never leaves a stale lock). The
// file holds the holder's host and process id for the message a second
// study gets. On NFS, Linux maps flock to the server's byte-range locks.
#pragma once

#include <string>

namespace eqhb {

class StudyFolderLock {
 public:
  // Takes the lock without waiting. Throws InputError naming --out, the
  // folder and the holder if another process has it; IoError if the lock
  // file cannot be created or written.
  explicit StudyFolderLock(const std::string& dir);
  ~StudyFolderLock();
  StudyFolderLock(const StudyFolderLock&) = delete;
  StudyFolderLock& operator=(const StudyFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace eqhb
