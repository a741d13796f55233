// `solve --error-estimate` and `solve --accuracy TOL`: the error estimate of a
// harmonic-balance solution and the cheapest H that meets a tolerance
// (lib/eqhb/accuracy).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>

#include "eqhb/accuracy/accuracy_target.h"
#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/scenes/law_rho.h"
#include "scene_arguments.h"

namespace eqhb::cli {

struct AccuracyArguments {
  bool error_estimate = false;      // --error-estimate: one more solve at 2H
  std::optional<double> tolerance;  // --accuracy TOL
  int max_harmonics = 320;          // --max-harmonics
};

void addAccuracyOptions(CLI::App* command, AccuracyArguments& args);

// The ρ that --accuracy chooses from: each law's own ρ times kRhoFactors,
// or the scene as given when --rho is given or no law has ρ.
constexpr double kRhoFactors[] = {1.0, 0.1, 0.01};
struct RhoCandidates {
  std::vector<HbModel> models;   // the scene with every override, ρ scaled
  std::vector<double> factors;   // one per model
  std::vector<std::optional<RhoSetting>> scene_rho;  // per law, nullopt for a law without ρ
};
RhoCandidates rhoCandidates(const SceneArguments& scene);
// The overrides that give every law with ρ its ρ times `factor`.
std::vector<std::string> scaledRhoOverrides(const std::vector<std::optional<RhoSetting>>& scene_rho, double factor);
// The chosen ρ: one number when every law with ρ has the same, else one
// per law (null for a law without); "scene" when no law has ρ. A scale-free
// ρ reads {"rho_factor": f}.
nlohmann::json rhoJson(const std::vector<std::optional<RhoSetting>>& scene_rho, double factor);

// {"max_abs", "coefficients", "max_abs_difference", "factor", "method",
//  "refined_harmonics", "refined_samples", "refined_converged"}
nlohmann::json errorEstimateJson(const ErrorEstimate& estimate);
// {"tolerance", "reached", "failure", "seconds", "ladder": [{harmonics, samples, converged, estimate, seconds}],
//  "rho_factor", "rho_candidates": [{"rho_factor", "ladder"}] (when chosen among several)}
nlohmann::json accuracyJson(const AccuracyChoice& choice, double tolerance, const std::vector<double>& factors = {1.0});

}  // namespace eqhb::cli
