// What one harmonic-balance solve of a scene does, for every interface (the
// eqhb command's `solve`, Python's eqhb.solve): the backend and its limits,
// how it starts, what it tries after a failure, and what is computed on the
// answer. Defaults are those of `eqhb solve`.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "eqhb/solvers/solver.h"

namespace eqhb::app {

struct SolveOptions {
  std::string solver = "dogleg";  // a registered backend (registeredSolvers)
  bool condensed = true;          // false: the full system [x; λ]
  // Tolerance, iteration, evaluation and time limits, linear algebra and the
  // backend's own NAME -> VALUE settings. time_limit bounds the set-up too.
  SolverOptions solver_options;
  // Steps after a failed solve: "default", "none", or "cold,full,condensed,NAME,..."
  // (default_path.h).
  std::string fallback = "default";
  // Without from_harmonics or initial: "coarse" (a coarse harmonic balance
  // first, coarse_start.h) or "zero".
  std::string cold_start = "coarse";
  // Start from the solutions at H₀, 2H₀, ... below the scene's H
  // (continuation in H); >= 1 and below H.
  std::optional<int> from_harmonics;
  // The start [x; λ] in the full layout (a solution's "full"); empty: none.
  Eigen::VectorXd initial;
  int repeat = 1;  // solves timed (the median reported), in [1, 100000]

  bool stability = false;       // Floquet multipliers (converged solutions)
  std::string stability_method = "hill";  // hill, monodromy or auto (HillOptions::method)
  bool error_estimate = false;  // the relative error of max|x| by one more solve at 2H
  // The cheapest H (and ρ unless the scene's settings fix one) whose
  // estimated relative error of max|x| is <= accuracy, in (0, 1).
  std::optional<double> accuracy;
  int max_harmonics = 320;      // with accuracy: the largest H solved

  std::string refine;           // "" or "shoot": harmonic balance followed by shooting
  double restitution = 0.0;     // with refine: Newton impact coefficient of contact laws, in [0, 1]
  int refine_harmonics = 0;     // with refine: H of the orbit's truncation (0: the solve's), >= 0

  // False with a message naming the field, its value and the rule.
  bool isValid(std::string* why) const;
};

// Throws InputError with isValid's message.
void validate(const SolveOptions& options);

}  // namespace eqhb::app
