// The cheapest number of harmonics whose estimated error meets a tolerance:
// solve at H₀, estimate by one solve at 2H₀ (error_estimate.h); if the
// estimate is above the tolerance, the 2H₀ solution becomes the candidate and
// is itself checked at 4H₀, and so on up to a largest H. N follows H
// (withHarmonics). Each rung costs one solve, warm-started from the rung below.
#pragma once

#include <string>
#include <vector>

#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

struct AccuracyRung {
  int harmonics = 0;
  int samples = 0;
  bool converged = false;    // the solve at this H
  double estimate = 0.0;     // estimated relative error of max|x| (needs the rung above)
  bool estimated = false;
  double seconds = 0.0;      // the solve at this H
};

struct AccuracyChoice {
  bool reached = false;
  std::string failure;       // why not reached
  HbModel model;             // the chosen discretisation (the last tried if not reached)
  Eigen::VectorXd full;      // its solution, FullSystem layout
  SolverResult result;       // the solve that produced it
  ErrorEstimate estimate;    // its estimate
  std::vector<AccuracyRung> ladder;
  double seconds = 0.0;      // all solves
};

// tolerance in (0, 1), 1 <= start_harmonics <= max_harmonics; throws
// InputError naming --accuracy or --max-harmonics otherwise.
AccuracyChoice chooseHarmonics(const HbModel& model, double tolerance, int start_harmonics, int max_harmonics,
                               Solver& solver, const SolverOptions& options, bool condensed);

}  // namespace eqhb
