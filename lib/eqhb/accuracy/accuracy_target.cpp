#include "eqhb/accuracy/accuracy_target.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

namespace {

void checkLadderArguments(double tolerance, int start_harmonics, int max_harmonics, const AccuracyTestOptions& test) {
  if (!std::isfinite(test.safety_factor) || test.safety_factor <= 0.0)
    throwInputError("safety_factor", formatNumber(test.safety_factor), "must be finite and > 0");
  if (!std::isfinite(tolerance) || tolerance <= 0.0 || tolerance >= 1.0)
    throwInputError("accuracy", formatNumber(tolerance), "must be a relative error in (0, 1)");
  if (max_harmonics < 1 || max_harmonics > 100000)
    throwInputError("max_harmonics", std::to_string(max_harmonics), "must be in [1, 100000]");
  if (start_harmonics < 1 || start_harmonics > max_harmonics)
    throwInputError("harmonics", std::to_string(start_harmonics),
                    "the first H tried must be in [1, max_harmonics = " + std::to_string(max_harmonics) + "]");
}

// What every rung of one ladder shares.
struct Ladder {
  double tolerance;
  int max_harmonics;
  Solver& solver;
  const SolverOptions& options;
  bool condensed;
  AccuracyTestOptions test;
  const FallbackChain& fallbacks;  // the first rung's
  FallbackChain above = fallbacks.withOwnBackendOnly();  // the rungs above it
  double seconds = 0.0;  // every solve and shot of every candidate
};

// One candidate on its ladder: its state as returned, whether it is still
// climbing, and why the exact test does not apply to it (empty: it does).
struct Climber {
  AccuracyChoice state;
  bool live = true;
  std::string exact_unavailable;
};

Climber startClimber(const HbModel& model, const AccuracyTestOptions& test) {
  Climber c;
  c.state.model = model;
  c.state.safety_factor = test.safety_factor;
  c.exact_unavailable =
      test.choice == AccuracyTestChoice::kEstimate ? "accuracy_test = estimate" : exactOrbitUnavailable(model);
  return c;
}

void drop(Climber& c, const std::string& why) {
  c.live = false;
  c.state.failure = why;
}

std::string atH(int harmonics) { return "H = " + std::to_string(harmonics); }

std::string nothingConverged(const FallbackChain& tried) {
  return tried.steps.empty() ? "" : ", nor did any fallback step";
}

// The candidate's solution at 2H, from its solution at H padded with zeros
// (estimateError, which also compares the two): the estimate of the rung
// and the start of the next. Drops the candidate when that solve fails.
bool solveAbove(Ladder& in, Climber& c) {
  AccuracyChoice& s = c.state;
  if (s.estimate.refined_harmonics == 2 * s.model.basis.count()) return s.estimate.available;  // solved already
  s.estimate = estimateError(s.model, s.full, in.solver, in.options, in.condensed, &in.above);
  in.seconds += s.estimate.refined.seconds;
  AccuracyRung& rung = s.ladder.back();
  rung.estimate = s.estimate.max_abs;
  rung.estimated = true;
  AccuracyRung above;
  above.harmonics = s.estimate.refined_harmonics;
  above.samples = s.estimate.refined_samples;
  above.converged = s.estimate.available;
  above.seconds = s.estimate.refined.seconds;
  above.fallback = s.estimate.fallback;
  s.ladder.push_back(above);
  if (!s.estimate.available)
    drop(c, "the solve at " + atH(s.estimate.refined_harmonics) + " (started from the solution at " +
                atH(s.model.basis.count()) + ") did not converge (" +
                terminationName(s.estimate.refined.termination) + ")" + nothingConverged(in.above));
  return s.estimate.available;
}

// Tests the candidate's solution at its H: the exact orbit where it applies
// and the shot converges, else the estimate with its safety factor. Drops
// the candidate when no test can be made.
void testRung(Ladder& in, Climber& c) {
  AccuracyChoice& s = c.state;
  const int harmonics = s.model.basis.count();
  const size_t tested = s.ladder.size() - 1;
  s.estimate = ErrorEstimate();  // none yet at this rung
  s.test_note = c.exact_unavailable;
  if (c.exact_unavailable.empty()) {
    const ExactOrbitError exact = exactOrbitError(s.model, s.full);
    in.seconds += exact.seconds;
    s.ladder[tested].test_seconds = exact.seconds;
    if (exact.converged) {
      s.test = AccuracyTest::kExactOrbit;
      s.error = exact.error;
    } else {
      s.test_note = "the exact orbit at " + atH(harmonics) + ": " + exact.failure;
    }
  }
  if (!s.test_note.empty()) {
    if (2 * harmonics > in.max_harmonics) {
      drop(c, "the error estimate at " + atH(harmonics) + " needs a solve at 2H, above max_harmonics = " +
                  std::to_string(in.max_harmonics));
      return;
    }
    if (!solveAbove(in, c)) return;
    s.test = AccuracyTest::kEstimate;
    s.error = s.safety_factor * s.estimate.max_abs;
  }
  AccuracyRung& rung = s.ladder[tested];
  rung.tested = true;
  rung.test = s.test;
  rung.error = s.error;
}

// The tested value as the failure message gives it.
std::string testedValue(const AccuracyChoice& s) {
  if (s.test == AccuracyTest::kExactOrbit) return "exact-orbit error " + formatNumber(s.error);
  return "estimate " + formatNumber(s.estimate.max_abs) + " x safety factor " + formatNumber(s.safety_factor) +
         " = " + formatNumber(s.error);
}

// The H the next rung needs solved to be tested as this one was: 2H for the
// exact orbit, 4H for the estimate (its solve at twice the next H).
int nextTestHarmonics(const AccuracyChoice& s) {
  const int harmonics = s.model.basis.count();
  return s.test == AccuracyTest::kExactOrbit ? 2 * harmonics : 4 * harmonics;
}

size_t firstLive(const std::vector<Climber>& climbers) {
  for (size_t k = 0; k < climbers.size(); ++k)
    if (climbers[k].live) return k;
  return climbers.size();
}

// Every climber from its first rung (solved: converged or dropped) until one
// meets the tolerance, all are dropped, or the next rung would be above
// max_harmonics. Returns the index of the climber to report.
size_t climb(Ladder& in, std::vector<Climber>& climbers) {
  const size_t none = climbers.size();
  while (true) {
    if (firstLive(climbers) == none) return 0;
    size_t best = none;
    for (size_t k = 0; k < climbers.size(); ++k) {
      if (!climbers[k].live) continue;
      testRung(in, climbers[k]);
      if (!climbers[k].live) continue;
      if (best == none || climbers[k].state.error < climbers[best].state.error) best = k;
    }
    if (best == none) return 0;
    AccuracyChoice& winner = climbers[best].state;
    const int harmonics = winner.model.basis.count();
    if (winner.error <= in.tolerance) {
      winner.reached = true;
      return best;
    }
    if (nextTestHarmonics(winner) > in.max_harmonics) {
      // The reported solution stays the last one tested.
      winner.failure = testedValue(winner) + " at " + atH(harmonics) + "; the next rung needs a solve at " +
                       atH(nextTestHarmonics(winner)) + ", above max_harmonics = " + std::to_string(in.max_harmonics);
      return best;
    }
    const double best_error = winner.error;
    for (Climber& c : climbers) {
      if (!c.live) continue;
      AccuracyChoice& s = c.state;
      if (harmonics >= kPruneFromHarmonics && s.error > kPruneFactor * best_error) {
        drop(c, "dropped at " + atH(harmonics) + ": " + testedValue(s) + " > " + formatNumber(kPruneFactor) +
                    " x the best");
        continue;
      }
      if (!solveAbove(in, c)) continue;
      // The solution at 2H is the next candidate.
      s.model = withHarmonics(s.model, s.estimate.refined_harmonics);
      s.full = s.estimate.refined_full;
      s.result = s.estimate.refined;
    }
  }
}

// The chosen climber's state with the totals of all.
AccuracyChoice finish(const Ladder& in, const std::vector<Climber>& climbers, size_t chosen) {
  AccuracyChoice out = climbers[chosen].state;
  out.candidate = static_cast<int>(chosen);
  out.seconds = in.seconds;
  for (const auto& c : climbers) out.candidate_ladders.push_back(c.state.ladder);
  if (climbers.size() > 1 && !out.reached && out.failure.empty()) out.failure = "no candidate reached the tolerance";
  return out;
}

// The first rung's solve from zero, then the fallback steps if it failed
// (`fallback`: the step that converged, if one did).
SolverResult solveFirstRung(HbSystem& system, const Ladder& in, std::string* fallback) {
  SolverResult result = in.solver.solve(system, Eigen::VectorXd::Zero(system.size()), in.options);
  if (result.converged() || in.fallbacks.steps.empty()) return result;
  FallbackReport report;
  const double first_seconds = result.seconds;
  // From zero is not the cold start of a solve (the coarse one): the chain's
  // "cold" step applies.
  result = solveWithFallbacks(system, in.solver, in.options, result, false, in.fallbacks, &report);
  result.seconds = first_seconds + report.seconds;
  *fallback = report.taken;
  return result;
}

AccuracyRung firstRung(const HbModel& model, const SolverResult& result) {
  AccuracyRung rung;
  rung.harmonics = model.basis.count();
  rung.samples = model.samples;
  rung.converged = result.converged();
  rung.seconds = result.seconds;
  return rung;
}

}  // namespace

AccuracyChoice chooseHarmonics(const HbModel& scene_model, double tolerance, int start_harmonics, int max_harmonics,
                               Solver& solver, const SolverOptions& options, bool condensed,
                               const AccuracyTestOptions& test, const FallbackChain& fallbacks) {
  return chooseDiscretisation({scene_model}, tolerance, start_harmonics, max_harmonics, solver, options, condensed,
                              test, fallbacks);
}

AccuracyChoice chooseDiscretisation(const std::vector<HbModel>& candidates, double tolerance, int start_harmonics,
                                    int max_harmonics, Solver& solver, const SolverOptions& options, bool condensed,
                                    const AccuracyTestOptions& test, const FallbackChain& fallbacks) {
  checkLadderArguments(tolerance, start_harmonics, max_harmonics, test);
  if (candidates.empty()) throw std::invalid_argument("chooseDiscretisation: no candidate model");
  Ladder in{tolerance, max_harmonics, solver, options, condensed, test, fallbacks};
  std::vector<Climber> climbers;
  for (const HbModel& candidate : candidates) {
    Climber c = startClimber(withHarmonics(candidate, start_harmonics), test);
    AccuracyChoice& s = c.state;
    auto system = makeHbSystem(s.model, condensed, options.linear_algebra);
    std::string fallback;
    s.result = solveFirstRung(*system, in, &fallback);
    s.full = system->fullCoefficients(s.result.solution);
    in.seconds += s.result.seconds;
    s.ladder.push_back(firstRung(s.model, s.result));
    s.ladder.back().fallback = fallback;
    if (!s.result.converged())
      drop(c, "the solve at " + atH(start_harmonics) + " did not converge (" +
                  terminationName(s.result.termination) + ")" + nothingConverged(in.fallbacks));
    climbers.push_back(std::move(c));
  }
  return finish(in, climbers, climb(in, climbers));
}

AccuracyChoice refineToAccuracy(const HbModel& model, const Eigen::VectorXd& full, const SolverResult& result,
                                double tolerance, int max_harmonics, Solver& solver, const SolverOptions& options,
                                bool condensed, const AccuracyTestOptions& test, const FallbackChain& fallbacks) {
  checkLadderArguments(tolerance, model.basis.count(), max_harmonics, test);
  Ladder in{tolerance, max_harmonics, solver, options, condensed, test, fallbacks};
  std::vector<Climber> climbers{startClimber(model, test)};
  AccuracyChoice& s = climbers[0].state;
  s.full = full;
  s.result = result;
  // The given solve is not counted in `seconds`: it belongs to the caller.
  s.ladder.push_back(firstRung(model, result));
  if (result.converged()) climb(in, climbers);
  else
    drop(climbers[0], "the solve at " + atH(model.basis.count()) + " did not converge (" +
                          terminationName(result.termination) + ")");
  AccuracyChoice out = climbers[0].state;
  out.seconds = in.seconds;
  return out;
}

}  // namespace eqhb
