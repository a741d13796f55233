// eqhb-bench's command line: what to run, where to write, how often to
// repeat each solve.
#pragma once

#include <string>

namespace eqhb::bench {

struct BenchOptions {
  std::string problems;        // folder of scene files (default: the shipped problems)
  std::string out = "results"; // output folder
  bool quick = false;          // fewer backends, forms and repeats
  bool scale_only = false;     // the scale study alone
  bool compliant_only = false; // the compliant-vs-Signorini study alone
  bool scenes_only = false;    // the scene study alone (bench.json, bench.csv, scenes.md)
  int repeats = 7;             // solves per case for the median time (at most 3 with quick)
  double reference_step = 2e-4;  // time step of the time-domain references
};

// Reads the command line into `options` (and the verbosity options). Returns
// false when the program should stop at once (--help, bad arguments), with
// the exit code in `exit_code`.
bool parseBenchOptions(int argc, char** argv, BenchOptions& options, int& exit_code);

}  // namespace eqhb::bench
