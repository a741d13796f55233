// Progress of a long run on stderr: "label  done/total  elapsed  ETA  detail".
// On a terminal the line is redrawn in place; elsewhere (a log, a pipe) it is
// off unless forced (--progress), then one plain line at most every few
// seconds. --quiet turns it off everywhere.
#pragma once

#include <chrono>
#include <string>

namespace eqhb::cli {

enum class ProgressMode { kAuto, kAlways, kNever };

class ProgressLine {
 public:
  ProgressLine(ProgressMode mode, std::string label);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool enabled() const { return enabled_; }
  // `fraction` of the work done, in [0, 1], sets the ETA (elapsed·(1−f)/f);
  // a negative fraction means unknown (no ETA). `count` is shown as is.
  void update(double fraction, const std::string& count, const std::string& detail = "");
  // Prints one line of text on stderr, whatever the mode, without mixing it
  // with a progress line being redrawn (which comes back at the next update).
  void message(const std::string& text);
  // Ends the line (a newline on a terminal), showing the total time.
  void finish(const std::string& detail = "");
  double elapsedSeconds() const;

 private:
  void print(double fraction, const std::string& count, const std::string& detail, bool last);

  bool enabled_ = false, terminal_ = false, finished_ = false, printed_ = false;
  std::string label_;
  std::chrono::steady_clock::time_point start_, last_print_;
  size_t last_width_ = 0;
};

// "12.3 s", "4 min 05 s", "1 h 02 min": for elapsed times and ETAs.
std::string formatDuration(double seconds);

}  // namespace eqhb::cli
