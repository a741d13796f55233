// The cheapest number of harmonics whose error of max|x| meets a tolerance:
// solve at H₀ and test it (rung_test.h: the true error against the exact
// orbit shot from it where the scene allows, else the estimate by one solve
// at 2H₀ times a safety factor); if the test fails, the 2H₀ solution becomes
// the candidate and is itself tested, and so on up to a largest H. N follows
// H (withHarmonics). Each rung costs one solve, warm-started from the rung
// below, and its test (a shot, or the solve at 2H that is the next rung).
#pragma once

#include <string>
#include <vector>

#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/accuracy/rung_test.h"
#include "eqhb/continuation/fallback_chain.h"
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
  bool tested = false;       // the rung's solution was tested (exact orbit or estimate)
  AccuracyTest test = AccuracyTest::kEstimate;
  double error = 0.0;        // the tested value: the true error, or the safety factor × the estimate
  double test_seconds = 0.0; // the shot of the exact test (the estimate's solve is the next rung's)
  std::string fallback;      // the fallback step that converged this rung's solve (empty: none needed)
};

// Which tests a ladder may use (rung_test.h).
struct AccuracyTestOptions {
  AccuracyTestChoice choice = AccuracyTestChoice::kAuto;
  // The estimate's safety factor; other values than the calibrated one are
  // for measuring it (bench/accuracy_tally.h), > 0.
  double safety_factor = kEstimateSafetyFactor;
};

struct AccuracyChoice {
  bool reached = false;
  int candidate = 0;         // chooseDiscretisation: the index of the chosen candidate model
  std::string failure;       // why not reached
  HbModel model;             // the chosen discretisation (the last tried if not reached)
  Eigen::VectorXd full;      // its solution, FullSystem layout
  SolverResult result;       // the solve that produced it
  ErrorEstimate estimate;    // its estimate (refined_harmonics = 0: none, the exact test decided first)
  AccuracyTest test = AccuracyTest::kEstimate;  // the test of the last rung tested
  double error = 0.0;        // its value, compared with the tolerance
  double safety_factor = kEstimateSafetyFactor;  // of the estimate test
  // Why the estimate decided where the exact orbit was asked for ("auto"):
  // the laws or size of the scene, or a shot that did not converge; empty
  // when the exact orbit decided.
  std::string test_note;
  std::vector<AccuracyRung> ladder;
  std::vector<std::vector<AccuracyRung>> candidate_ladders;  // chooseDiscretisation: every candidate's rungs
  double seconds = 0.0;      // all solves (of every candidate)

  // A rung was tested: `test` and `error` hold (not when the first solve
  // failed, nor when no test could be made below max_harmonics).
  bool tested() const {
    for (const AccuracyRung& r : ladder)
      if (r.tested) return true;
    return false;
  }
};

// The same ladder run side by side on several candidate models of one scene
// (the same scene with ρ scaled, say): at every rung each live candidate is
// tested; the first rung where one meets the tolerance decides (the
// smallest tested error among them). From H >= kPruneFromHarmonics on, where
// rungs start to cost, a candidate whose tested error is more than
// kPruneFactor times the rung's best is dropped (about one doubling of H
// behind at the measured H^-1 rate). A candidate whose solve fails is
// dropped; the choice fails when every candidate has. The ladder stops when
// the next rung could not be tested below max_harmonics (2H for the exact
// test, 4H for the estimate's solve).
// A rung's solve that fails gets `fallbacks`' steps (the default path of a
// solve, fallback_chain.h) before its candidate is dropped: the first rung
// starts from zero, where a penalty wall at ω = 0.5 (k_n = 100) needs the
// coarse start and ω = 0.7 another backend; the rungs above get the steps
// of the chain that rerun the own backend (withOwnBackendOnly); an empty
// chain drops a candidate at its first failed solve.
constexpr int kPruneFromHarmonics = 20;
constexpr double kPruneFactor = 2.0;
AccuracyChoice chooseDiscretisation(const std::vector<HbModel>& candidates, double tolerance, int start_harmonics,
                                    int max_harmonics, Solver& solver, const SolverOptions& options, bool condensed,
                                    const AccuracyTestOptions& test = {}, const FallbackChain& fallbacks = {});

// One candidate: chooseDiscretisation({model}).
// tolerance in (0, 1), 1 <= start_harmonics <= max_harmonics; throws
// InputError naming accuracy or max_harmonics otherwise.
AccuracyChoice chooseHarmonics(const HbModel& model, double tolerance, int start_harmonics, int max_harmonics,
                               Solver& solver, const SolverOptions& options, bool condensed,
                               const AccuracyTestOptions& test = {}, const FallbackChain& fallbacks = {});

// The same ladder from a solution already at hand (`full`, from `result`, on
// `model`'s H and N): test it and climb from there. The given solve is
// the first rung but its time is not in `seconds`. Same argument checks, with
// the model's H as the first H.
AccuracyChoice refineToAccuracy(const HbModel& model, const Eigen::VectorXd& full, const SolverResult& result,
                                double tolerance, int max_harmonics, Solver& solver, const SolverOptions& options,
                                bool condensed, const AccuracyTestOptions& test = {},
                                const FallbackChain& fallbacks = {});

}  // namespace eqhb
