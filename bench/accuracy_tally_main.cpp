// eqhb-accuracy-tally: does `solve --accuracy TOL` hold against the exact
// orbits? Prints the Markdown table and tally of bench/accuracy_tally.h;
// --accuracy-test estimate measures the estimate's test alone (the safety
// factor's calibration check).
#include <CLI/CLI.hpp>
#include <iostream>

#include "accuracy_tally.h"

int main(int argc, char** argv) {
  CLI::App app{"solve --accuracy TOL against exact orbits over many cases"};
  eqhb::bench::TallyOptions options;
  app.add_option("--tolerance", options.tolerance, "TOL of --accuracy")->capture_default_str();
  app.add_option("--max-harmonics", options.max_harmonics, "--max-harmonics of the solves")->capture_default_str();
  app.add_option("--accuracy-test", options.accuracy_test, "auto or estimate")->capture_default_str();
  app.add_option("--safety-factor", options.safety_factor, "The estimate's safety factor (to calibrate it)")
      ->capture_default_str();
  app.add_option("--only", options.only, "Only the cases whose scene file name contains this text");
  CLI11_PARSE(app, argc, argv);
  std::cout << eqhb::bench::accuracyTally(eqhb::bench::accuracyTallyCases(), options) << std::flush;
  return 0;
}
