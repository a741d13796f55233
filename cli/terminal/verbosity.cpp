#include "terminal/verbosity.h"

namespace eqhb::cli {

namespace {
Verbosity& mutableVerbosity() {
  static Verbosity v;
  return v;
}
}  // namespace

const Verbosity& verbosity() { return mutableVerbosity(); }

void addVerbosityOptions(CLI::App& app) {
  auto* progress = app.add_flag_callback(
      "--progress", [] { mutableVerbosity().progress = ProgressMode::kAlways; },
      "Show progress (elapsed time, ETA) on stderr even when it is not a terminal");
  auto* quiet = app.add_flag_callback(
      "--quiet,-q", [] { mutableVerbosity().progress = ProgressMode::kNever; }, "Never show progress");
  quiet->excludes(progress);
  app.add_flag_callback(
      "--verbose,-v", [] { mutableVerbosity().verbose = true; },
      "Print the resolved settings and per-step details on stderr");
}

}  // namespace eqhb::cli
