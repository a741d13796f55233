// The benchmark's progress on stderr: a line per study (elapsed, ETA) and
// each case's line with --verbose.
#pragma once

#include <sstream>
#include <string>

#include "terminal/progress.h"
#include "terminal/verbosity.h"

namespace eqhb::bench {

using cli::ProgressLine;

// Prints `text` on `line` with --verbose.
inline void note(ProgressLine& line, const std::string& text) {
  if (cli::verbosity().verbose) line.message(text);
}

// "what done/total".
inline std::string count(const char* what, size_t done, size_t total) {
  return std::string(what) + " " + std::to_string(done) + "/" + std::to_string(total);
}

// Its arguments printed one after the other.
template <class... Args>
std::string cat(const Args&... args) {
  std::ostringstream text;
  (text << ... << args);
  return text.str();
}

}  // namespace eqhb::bench
