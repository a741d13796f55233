// What the fallback steps that run several solves share (the forcing
// homotopy, continuation in ω): the cold start of one system, one time limit
// for the whole series, and the series' counts reported as one solve's.
#pragma once

#include <chrono>

#include <Eigen/Dense>

#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// The solve's own cold start on `system`: the coarse start, then
// `rest_full` (the full coefficients a cold solve begins at; empty: zero).
SolverResult solveCold(Solver& solver, HbSystem& system, const SolverOptions& options,
                       const Eigen::VectorXd& rest_full);

class SolveSeries {
 public:
  // The series begins now, under `options` (its time_limit, 0: none, bounds
  // the whole series).
  explicit SolveSeries(const SolverOptions& options);
  // The next solve's options: what is left of the time limit, at least a
  // thousandth of it (a solve given no time would report nothing).
  SolverOptions next() const;
  // Adds a solve's iterations and evaluations to the series'.
  void count(const SolverResult& solve);
  void countResidualEvaluations(int evaluations) { total_.residual_evaluations += evaluations; }
  // `last` (the series' last solve) with the series' counts and its time
  // since it began in place of its own.
  SolverResult total(SolverResult last) const;

 private:
  double seconds() const;
  SolverOptions options_;
  std::chrono::steady_clock::time_point start_;
  SolverResult total_;  // its counts only
};

}  // namespace eqhb
