// Files written with every call checked. A stream that hits a full disk sets
// its failbit and then drops every later write without a word; here the
// first failed write(2), fsync(2), close(2) or rename(2) throws IoError
// naming the file, so that a command stops there and says so.
#pragma once

#include <chrono>
#include <string>

namespace eqhb {

// A file open for appending (O_APPEND: each row one write at the end).
class AppendOnlyFile {
 public:
  // Creates the file if it is missing; throws IoError if it cannot be opened.
  explicit AppendOnlyFile(const std::string& path);
  ~AppendOnlyFile();
  AppendOnlyFile(const AppendOnlyFile&) = delete;
  AppendOnlyFile& operator=(const AppendOnlyFile&) = delete;
  // Writes all of `text`, then fdatasync if the last one is older than
  // `sync_interval` (file systems such as NFS report some failures only
  // there, and a sync per row would cost more than a sample).
  void append(const std::string& text);
  // fdatasync now.
  void sync();
  const std::string& path() const { return path_; }

  static constexpr std::chrono::seconds sync_interval{1};

 private:
  std::string path_;
  int fd_ = -1;
  std::chrono::steady_clock::time_point last_sync_;
};

// Replaces `path` by `text`: written to PATH.tmp, synced, renamed over PATH,
// so that a failed write leaves the previous file (or none), never a cut one.
void writeFileChecked(const std::string& path, const std::string& text);

}  // namespace eqhb
