// Running the helper scripts installed with the programs (the plotters):
// found relative to the running executable, run with an argument vector —
// no shell, so no quoting and nothing in a file name is interpreted.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace eqhb::cli {

// Runs argv[0] (searched on PATH when it has no '/') with argv and waits.
// Returns the exit status; throws std::runtime_error if it could not start
// or was killed by a signal.
int runProgram(const std::vector<std::string>& argv);

// Runs argv like runProgram and returns what it printed on stdout (stderr
// is discarded); nullopt if it could not start or did not exit with 0.
std::optional<std::string> programOutput(const std::vector<std::string>& argv);

// A file installed with the programs under share/eqhb: <exe dir>/../share/eqhb/NAME
// when installed, <exe dir>/share/eqhb/NAME in a build tree. Throws
// std::runtime_error naming the places looked at.
std::string findDataFile(const std::string& name);

// Debian's /usr/bin/python3 (the one with matplotlib) when present, else
// python3 from PATH.
std::string python3();

}  // namespace eqhb::cli
