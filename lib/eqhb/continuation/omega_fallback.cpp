#include "eqhb/continuation/omega_fallback.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "eqhb/continuation/secant_guess.h"
#include "eqhb/continuation/solve_series.h"
#include "eqhb/error.h"
#include "eqhb/preload/operating_point.h"

namespace eqhb {

namespace {

// How far one side got.
struct WalkOutcome {
  bool started = false;  // the cold start at its frequency converged
  int steps = 0;         // steps taken from there
  double reached = 0.0;  // the last ω solved
};

// One side: the cold start at `from`, then steps to the system's ω on
// `walk`, a system of its own. Returns the last solve (converged at ω on
// arrival); every solve is counted in `series`.
SolverResult walkFrom(double from, Solver& solver, const HbSystem& system, const StaticContactState* at_rest,
                      SolveSeries& series, WalkOutcome* outcome, std::unique_ptr<HbSystem>* walk) {
  const double target = system.model().omega;
  HbModel model = system.model();
  model.omega = from;
  *walk = makeHbSystem(model, system.condensed(), series.next().linear_algebra);
  HbSystem& w = **walk;
  const Eigen::VectorXd rest_full = at_rest ? linearisedStart(model, *at_rest, series.next()) : Eigen::VectorXd();
  SolverResult r = solveCold(solver, w, series.next(), rest_full);
  series.count(r);
  *outcome = WalkOutcome();
  outcome->reached = from;
  if (!r.converged()) return r;
  outcome->started = true;
  const double first_step = std::abs(target - from) / OmegaWalk::kStepsAcross;
  const double smallest = first_step / std::pow(2.0, OmegaWalk::kHalvings);
  const double direction = target > from ? 1.0 : -1.0;
  SecantGuess guess;
  guess.accept(from, r.solution);
  Eigen::VectorXd z = r.solution;
  double at = from, h = first_step;
  for (int solves = 1; solves < OmegaWalk::kMostSolves && h >= smallest; ++solves) {
    const double next = std::abs(target - at) <= h * (1.0 + 1e-12) ? target : at + direction * h;
    w.setOmega(next);
    int evaluations = 0;
    const Eigen::VectorXd start = guess.at(next, w, z, &evaluations);
    series.countResidualEvaluations(evaluations);
    r = solver.solve(w, start, series.next());
    series.count(r);
    if (r.termination == Termination::kTimeLimit) return r;
    if (!r.converged()) {
      h /= 2.0;
      continue;
    }
    ++outcome->steps;
    z = r.solution;
    at = next;
    outcome->reached = at;
    guess.accept(at, z);
    if (at == target) return r;
    h = std::min(2.0 * h, first_step);
  }
  if (r.converged()) r.termination = Termination::kNotProgressing;  // stopped short of ω
  return r;
}

}  // namespace

SolverResult solveByOmegaContinuation(Solver& solver, HbSystem& system, const SolverOptions& options,
                                      const StaticContactState* at_rest, std::string* note) {
  SolveSeries series(options);
  const double target = system.model().omega;
  SolverResult last;
  last.solver = solver.name();
  last.termination = Termination::kNotProgressing;
  std::string why;
  for (const double factor : {OmegaWalk::kBelow, OmegaWalk::kAbove}) {
    const double from = factor * target;
    WalkOutcome walked;
    std::unique_ptr<HbSystem> walk;
    last = walkFrom(from, solver, system, at_rest, series, &walked, &walk);
    if (last.converged()) {
      // The walk's answer at ω, polished on the caller's system: the result
      // is one of its solves (usually at once: the same equations).
      SolverResult polished =
          solver.solve(system, system.fromFullCoefficients(walk->fullCoefficients(last.solution)), series.next());
      series.count(polished);
      if (polished.converged()) {
        if (note)
          *note = why + (why.empty() ? "" : "; ") + "from omega = " + formatNumber(from) + " in " +
                  std::to_string(walked.steps) + " steps";
        last = polished;
        break;
      }
      last = polished;
    }
    if (!why.empty()) why += "; ";
    why += "from omega = " + formatNumber(from) +
           (walked.started ? ": stopped at " + formatNumber(walked.reached) : ": its cold start failed");
    if (last.termination == Termination::kTimeLimit) break;
  }
  if (!last.converged() && note) *note = why;
  return series.total(last);
}

}  // namespace eqhb
