// The options every application call that solves shares, declared once so
// that each interface reads them in one place: which backend solves, on
// which system, with which limits, and what follows a failed solve
// (SolverChoice); what is computed on converged solutions (SolutionChecks).
// SolveOptions, SweepOptions and StudyOptions extend them.
#pragma once

#include <optional>
#include <string>

#include "eqhb/option_refusal.h"
#include "eqhb/solvers/solver.h"

namespace eqhb::app {

struct SolverChoice {
  std::string solver = "dogleg";  // a registered backend (registeredSolvers)
  bool condensed = true;          // false: the full system [x; λ]
  // Tolerance, iteration, evaluation and time limits, linear algebra and the
  // backend's own NAME -> VALUE settings. time_limit bounds the set-up too.
  SolverOptions solver_options;
  // Steps after a failed solve (on a curve: a point that fails after its
  // halved steps, and the first point): "default", "none", or
  // "cold,full,condensed,NAME,..." (default_path.h).
  std::string fallback = "default";
};

struct SolutionChecks {
  bool stability = false;  // Floquet multipliers of each converged solution
  std::string stability_method = "auto";  // hill, monodromy, shooting or auto (HillOptions::method)
  double stability_time_limit = 0.0;  // seconds for a curve's stability, 0: none (HillOptions::time_limit)
  bool error_estimate = false;  // per converged solution, the relative error of max|x| by one more solve at 2H
  // The cheapest H (and ρ unless the scene's settings fix one) whose
  // relative error of max|x| is <= accuracy, in (0, 1), by accuracy_test.
  // On a curve: chosen at the first point, doubling from the settings'
  // harmonics or min(5, H), then raised on the points whose test fails.
  std::optional<double> accuracy;
  int max_harmonics = 320;  // with accuracy: the largest H solved
  // With accuracy, the test of each rung (accuracy/rung_test.h): "auto" (the
  // true error against the exact orbit where every law has an exact flow and
  // the structure is small, else the estimate times its safety factor) or
  // "estimate" (always the latter).
  std::string accuracy_test = "auto";

  // False with a message naming the first bad field, its value and the rule
  // (stability_method, stability_time_limit, accuracy_test).
  bool isValid(std::string* why) const;
};

}  // namespace eqhb::app
