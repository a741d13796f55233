#include "bench_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>

#include "terminal/verbosity.h"

namespace eqhb::bench {

bool parseBenchOptions(int argc, char** argv, BenchOptions& options, int& exit_code) {
  CLI::App app{"eqhb-bench: solvers x formulations on every scene"};
  options.problems = EQHB_PROBLEMS_DIR;
  app.add_option("--problems", options.problems, "Folder of scene files");
  app.add_option("--out", options.out, "Output folder");
  app.add_flag("--quick", options.quick, "Short run: fewer backends, forms and repeats");
  app.add_flag("--scale-only", options.scale_only, "Run the scale study alone (scale.csv, scale.md)");
  app.add_flag("--compliant-only", options.compliant_only,
               "Run the compliant-vs-Signorini study alone (compliant.csv, compliant.md)");
  app.add_flag("--scenes-only", options.scenes_only,
               "Run the scene study alone: every scene, form, system and backend with the advice (scenes.md)");
  app.add_option("--repeats", options.repeats, "Solves per case for the median time (capped at ~1 s per case)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--reference-step", options.reference_step, "Time step of the time-domain references");
  eqhb::cli::addVerbosityOptions(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    exit_code = app.exit(e);
    return false;
  }
  if (options.quick) options.repeats = std::min(options.repeats, 3);
  return true;
}

}  // namespace eqhb::bench
