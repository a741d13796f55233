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
  int candidate = 0;         // chooseDiscretisation: the index of the chosen candidate model
  std::string failure;       // why not reached
  HbModel model;             // the chosen discretisation (the last tried if not reached)
  Eigen::VectorXd full;      // its solution, FullSystem layout
  SolverResult result;       // the solve that produced it
  ErrorEstimate estimate;    // its estimate
  std::vector<AccuracyRung> ladder;
  std::vector<std::vector<AccuracyRung>> candidate_ladders;  // chooseDiscretisation: every candidate's rungs
  double seconds = 0.0;      // all solves (of every candidate)
};

// The same ladder run side by side on several candidate models of one scene
// (the same scene with ρ scaled, say): at every rung each live candidate is
// estimated; the first rung where one meets the tolerance decides (the
// smallest estimate among them). From H >= kPruneFromHarmonics on, where
// rungs start to cost, a candidate whose estimate is more than
// kPruneFactor times the rung's best is dropped (about one doubling of H
// behind at the measured H^-1 rate). A candidate whose solve fails is
// dropped; the choice fails when every candidate has.
constexpr int kPruneFromHarmonics = 20;
constexpr double kPruneFactor = 2.0;
AccuracyChoice chooseDiscretisation(const std::vector<HbModel>& candidates, double tolerance, int start_harmonics,
                                    int max_harmonics, Solver& solver, const SolverOptions& options, bool condensed);

// One candidate: chooseDiscretisation({model}).
// tolerance in (0, 1), 1 <= start_harmonics <= max_harmonics; throws
// InputError naming accuracy or max_harmonics otherwise.
AccuracyChoice chooseHarmonics(const HbModel& model, double tolerance, int start_harmonics, int max_harmonics,
                               Solver& solver, const SolverOptions& options, bool condensed);

// The same ladder from a solution already at hand (`full`, from `result`, on
// `model`'s H and N): estimate at 2H and climb from there. The given solve is
// the first rung but its time is not in `seconds`. Same argument checks, with
// the model's H as the first H.
AccuracyChoice refineToAccuracy(const HbModel& model, const Eigen::VectorXd& full, const SolverResult& result,
                                double tolerance, int max_harmonics, Solver& solver, const SolverOptions& options,
                                bool condensed);

}  // namespace eqhb
