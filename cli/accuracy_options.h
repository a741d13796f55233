// `solve --error-estimate` and `solve --accuracy TOL`: the error estimate of a
// harmonic-balance solution and the cheapest H that meets a tolerance
// (lib/eqhb/accuracy).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>

#include "eqhb/accuracy/accuracy_target.h"
#include "eqhb/accuracy/error_estimate.h"

namespace eqhb::cli {

struct AccuracyArguments {
  bool error_estimate = false;      // --error-estimate: one more solve at 2H
  std::optional<double> tolerance;  // --accuracy TOL
  int max_harmonics = 320;          // --max-harmonics
};

void addAccuracyOptions(CLI::App* command, AccuracyArguments& args);

// {"max_abs", "coefficients", "max_abs_difference", "factor", "method",
//  "refined_harmonics", "refined_samples", "refined_converged"}
nlohmann::json errorEstimateJson(const ErrorEstimate& estimate);
// {"tolerance", "reached", "failure", "seconds", "ladder": [{harmonics, samples, converged, estimate, seconds}]}
nlohmann::json accuracyJson(const AccuracyChoice& choice, double tolerance);

}  // namespace eqhb::cli
