// The command line's global output switches, set once from the command line
// (--progress / --quiet, --verbose) and read by every command.
#pragma once

#include <CLI/CLI.hpp>

#include "terminal/progress.h"

namespace eqhb::cli {

struct Verbosity {
  ProgressMode progress = ProgressMode::kAuto;
  bool verbose = false;  // settings and per-step details on stderr
};

const Verbosity& verbosity();
// Adds --progress, --quiet and --verbose to `app` (usable after a subcommand
// too when the app falls through).
void addVerbosityOptions(CLI::App& app);

}  // namespace eqhb::cli
