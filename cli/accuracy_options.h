// `solve --error-estimate` and `solve --accuracy TOL` (lib/eqhb/accuracy,
// app::SolveOptions): the flags, and the names sweep reads them with.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>

#include "eqhb/app/rho_candidates.h"
#include "eqhb/app/solve_options.h"
#include "eqhb/output/solution_json.h"

namespace eqhb::cli {

struct AccuracyArguments {
  bool error_estimate = false;      // --error-estimate: one more solve at 2H
  std::optional<double> tolerance;  // --accuracy TOL
  int max_harmonics = app::SolutionChecks{}.max_harmonics;  // --max-harmonics
  std::string test = app::SolutionChecks{}.accuracy_test;   // --accuracy-test
};

void addAccuracyOptions(CLI::App* command, AccuracyArguments& args);
// --accuracy-test alone (sweep declares its own --accuracy).
void addAccuracyTestOption(CLI::App* command, AccuracyArguments& args);

using app::kRhoFactors;
using app::RhoCandidates;
using app::rhoCandidates;
using app::scaledRhoOverrides;
using output::accuracyJson;
using output::errorEstimateJson;
using output::rhoJson;

}  // namespace eqhb::cli
