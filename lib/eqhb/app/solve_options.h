// What one harmonic-balance solve of a scene does, for every interface (the
// eqhb command's `solve`, Python's eqhb.solve): the backend and its limits,
// how it starts, what it tries after a failure, and what is computed on the
// answer. Defaults are those of `eqhb solve`.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "eqhb/app/solver_choice.h"
#include "eqhb/orbits/default_restitution.h"

namespace eqhb::app {

// The backend, system, limits and fallbacks, and the stability, error
// estimate and accuracy target (solver_choice.h), with:
struct SolveOptions : SolverChoice, SolutionChecks {
  // Without from_harmonics or initial: "coarse" (a coarse harmonic balance
  // first, coarse_start.h) or "zero".
  std::string cold_start = "coarse";
  // Start from the solutions at H₀, 2H₀, ... below the scene's H
  // (continuation in H); >= 1 and below H.
  std::optional<int> from_harmonics;
  // The start [x; λ] in the full layout (a solution's "full"); empty: none.
  Eigen::VectorXd initial;
  int repeat = 1;  // solves timed (the median reported), in [1, 100000]

  std::string refine;           // "" or "shoot": harmonic balance followed by shooting
  // with refine: Newton impact coefficient of contact laws, in [0, 1]; by
  // default the one harmonic balance approaches (orbit_refinement.h)
  double restitution = orbits::kHarmonicBalanceRestitution;
  int refine_harmonics = 0;     // with refine: H of the orbit's truncation (0: the solve's), >= 0

  // False with a message naming the field, its value and the rule.
  bool isValid(std::string* why) const;
};

// Throws InputError with isValid's message.
void validate(const SolveOptions& options);

}  // namespace eqhb::app
