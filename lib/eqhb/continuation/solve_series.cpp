#include "eqhb/continuation/solve_series.h"

#include <algorithm>

#include "eqhb/continuation/coarse_start.h"

namespace eqhb {

SolverResult solveCold(Solver& solver, HbSystem& system, const SolverOptions& options,
                       const Eigen::VectorXd& rest_full) {
  CoarseStart start(system.model(), system.condensed(), options.linear_algebra);
  return start.solve(solver, system, options, nullptr, rest_full);
}

SolveSeries::SolveSeries(const SolverOptions& options)
    : options_(options), start_(std::chrono::steady_clock::now()) {}

double SolveSeries::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

SolverOptions SolveSeries::next() const {
  SolverOptions o = options_;
  if (options_.time_limit > 0.0)
    o.time_limit = std::max(options_.time_limit - seconds(), 1e-3 * options_.time_limit);
  return o;
}

void SolveSeries::count(const SolverResult& solve) {
  total_.iterations += solve.iterations;
  total_.residual_evaluations += solve.residual_evaluations;
  total_.jacobian_evaluations += solve.jacobian_evaluations;
}

SolverResult SolveSeries::total(SolverResult last) const {
  last.iterations = total_.iterations;
  last.residual_evaluations = total_.residual_evaluations;
  last.jacobian_evaluations = total_.jacobian_evaluations;
  last.seconds = seconds();
  return last;
}

}  // namespace eqhb
