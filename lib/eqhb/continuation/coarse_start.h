// A cold start from a coarse harmonic balance.
//
// From zero, a solve at H harmonics spends most of its iterations finding
// the shape of the orbit (where the laws stick, slip or close), which a few
// harmonics on few samples already carry at a fraction of the cost per
// iteration. The coarse problem keeps the fine one's harmonic set and
// everything else; it has about a third of the harmonics, (H + 1) / 3, and
// the smallest power of two of samples that gives four per period of the
// coarse basis' highest harmonic and at least 2k_max + 1 (never more than the
// fine N). Its solution, extended by zero harmonics, starts the fine solve.
//
// Measured on the shipped scenes (own dogleg, default options): the fine
// solve needs about half the iterations, and the coarse solve costs a small
// share of them (friction-1d: 26 iterations on 20 unknowns and 1024 samples
// become 18 coarse iterations on 6 unknowns and 32 samples plus 11 fine ones,
// 0.137 -> 0.073 ms).
// A coarse orbit can also be a poor start (an impact's timing at H/3): when
// the fine solve from it fails, it is solved again from zero, so the coarse
// start never loses a solution that the zero start finds.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// What the coarse start did in one solve.
struct ColdStartReport {
  bool used = false;              // false: the fine H is too small for a coarser rung
  int harmonics = 0, samples = 0; // the coarse problem
  SolverResult coarse;            // its solve
  bool retried_from_zero = false; // the fine solve from the coarse start failed
  SolverResult first_attempt;     // that failed fine solve (when retried)
  double seconds = 0.0;           // the whole cold start: coarse and fine solves
};

class CoarseStart {
 public:
  // Builds the coarse system once (patterns, plans, factorisations) for
  // solves of `fine`, at its ω, on the same system kind and linear algebra.
  // `deadline` bounds that set-up (TimeLimitReached).
  CoarseStart(const HbModel& fine, bool condensed, LinearAlgebra linear_algebra,
              const Deadline& deadline = Deadline());

  // Whether the fine problem has a coarser rung (H >= 4).
  bool available() const { return system_ != nullptr; }
  const HbModel& coarseModel() const { return coarse_; }

  // Solves `fine_system` (built on the fine model of the constructor) from
  // the coarse start, falling back to zero as described above (from zero
  // alone when !available()). Returns the fine result; `report` says what
  // happened. `rest_full`, when not empty, replaces zero: the full
  // coefficients on the fine model a cold solve begins at (a preload's
  // linearised response, operating_point.h); the coarse solve then starts
  // at its harmonics.
  SolverResult solve(Solver& solver, HbSystem& fine_system, const SolverOptions& options,
                     ColdStartReport* report, const Eigen::VectorXd& rest_full = Eigen::VectorXd());

 private:
  HbModel coarse_;
  std::unique_ptr<HbSystem> system_;
  Eigen::VectorXd zero_coarse_;
};

// The coarse model of `fine` (harmonics and samples as in the header), or
// the fine model itself when H < 4.
HbModel coarseModel(const HbModel& fine);

}  // namespace eqhb
