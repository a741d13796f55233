// `solve --refine shoot`: harmonic balance followed by shooting
// (lib/eqhb/orbits/orbit_refinement.h). The answer becomes the exact periodic
// orbit: its Fourier truncation on the same harmonics and its exact max|x|.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/orbits/orbit_refinement.h"

namespace eqhb::cli {

struct RefineArguments {
  std::string method;        // --refine: "" (none) or "shoot"
  double restitution = 0.0;  // --restitution of contact laws, in [0, 1]
  int harmonics = 0;         // --refine-harmonics: the truncation's H (0: the solve's)
};

void addRefineOptions(CLI::App* command, RefineArguments& args);

// Shoots from the harmonic-balance solution `full`; throws InputError for
// laws without an exact flow or a bad restitution.
orbits::RefinedSolution refine(const HbModel& model, const Eigen::VectorXd& full, const RefineArguments& args);

// The refined solution as the one reported: the truncation's coefficients,
// the exact orbit's max|x| per DOF.
HbSolution refinedSummary(const HbModel& model, const orbits::RefinedSolution& refined);

// {"method", "converged", "failure", "period_residual", "iterations",
//  "flow_evaluations", "harmonics", "samples", "seconds", "restitution",
//  "hb_max_abs": [per DOF, plain harmonic balance], "max_abs": [per DOF, exact]}
nlohmann::json refinementJson(const orbits::RefinedSolution& refined, const HbSolution& plain, double restitution);

}  // namespace eqhb::cli
