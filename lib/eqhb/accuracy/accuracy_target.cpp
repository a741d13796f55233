#include "eqhb/accuracy/accuracy_target.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

namespace {

void checkLadderArguments(double tolerance, int start_harmonics, int max_harmonics) {
  if (!std::isfinite(tolerance) || tolerance <= 0.0 || tolerance >= 1.0)
    throwInputError("accuracy", formatNumber(tolerance), "must be a relative error in (0, 1)");
  if (max_harmonics < 1 || max_harmonics > 100000)
    throwInputError("max_harmonics", std::to_string(max_harmonics), "must be in [1, 100000]");
  if (start_harmonics < 1 || start_harmonics > max_harmonics)
    throwInputError("harmonics", std::to_string(start_harmonics),
                    "the first H tried must be in [1, max_harmonics = " + std::to_string(max_harmonics) + "]");
}

// From a converged candidate (out.model, out.full, out.result, the last rung
// of out.ladder): estimate at 2H, and while the estimate is above the
// tolerance make the 2H solution the candidate, up to max_harmonics.
void climbLadder(double tolerance, int max_harmonics, Solver& solver, const SolverOptions& options, bool condensed,
                 AccuracyChoice& out) {
  const int first = out.model.basis.count();
  if (2 * first > max_harmonics) {
    out.failure = "the error estimate at H = " + std::to_string(first) +
                  " needs a solve at 2H, above max_harmonics = " + std::to_string(max_harmonics);
    return;
  }
  while (true) {
    out.estimate = estimateError(out.model, out.full, solver, options, condensed);
    out.seconds += out.estimate.refined.seconds;
    AccuracyRung& rung = out.ladder.back();
    rung.estimate = out.estimate.max_abs;
    rung.estimated = true;
    out.ladder.push_back({out.estimate.refined_harmonics, out.estimate.refined_samples, out.estimate.available, 0.0,
                          false, out.estimate.refined.seconds});
    const int h = out.model.basis.count();
    if (!out.estimate.available) {
      out.failure = "the solve at H = " + std::to_string(2 * h) + " (the error estimate at H = " + std::to_string(h) +
                    ") did not converge (" + terminationName(out.estimate.refined.termination) + ")";
      return;
    }
    if (out.estimate.max_abs <= tolerance) {
      out.reached = true;
      return;
    }
    if (4 * h > max_harmonics) {
      // The reported solution stays the last one with an estimate.
      out.failure = "estimate " + formatNumber(out.estimate.max_abs) + " at H = " + std::to_string(h) +
                    "; the next rung needs a solve at H = " + std::to_string(4 * h) + ", above max_harmonics = " +
                    std::to_string(max_harmonics);
      return;
    }
    // The refined solution is the next candidate.
    out.model = withHarmonics(out.model, out.estimate.refined_harmonics);
    out.full = out.estimate.refined_full;
    out.result = out.estimate.refined;
  }
}

}  // namespace

AccuracyChoice chooseHarmonics(const HbModel& scene_model, double tolerance, int start_harmonics, int max_harmonics,
                               Solver& solver, const SolverOptions& options, bool condensed) {
  return chooseDiscretisation({scene_model}, tolerance, start_harmonics, max_harmonics, solver, options, condensed);
}

AccuracyChoice chooseDiscretisation(const std::vector<HbModel>& candidates, double tolerance, int start_harmonics,
                                    int max_harmonics, Solver& solver, const SolverOptions& options, bool condensed) {
  checkLadderArguments(tolerance, start_harmonics, max_harmonics);
  if (candidates.empty()) throw std::invalid_argument("chooseDiscretisation: no candidate model");
  const size_t count = candidates.size();
  std::vector<AccuracyChoice> state(count);
  std::vector<bool> live(count, true);
  double seconds = 0.0;
  // What is returned: one candidate's state with the totals of all.
  auto finish = [&](size_t k) {
    AccuracyChoice out = state[k];
    out.candidate = static_cast<int>(k);
    out.seconds = seconds;
    for (const auto& s : state) out.candidate_ladders.push_back(s.ladder);
    if (count > 1 && !out.reached && out.failure.empty()) out.failure = "no candidate reached the tolerance";
    return out;
  };
  auto liveCount = [&] { return std::count(live.begin(), live.end(), true); };
  for (size_t k = 0; k < count; ++k) {
    AccuracyChoice& s = state[k];
    s.model = withHarmonics(candidates[k], start_harmonics);
    auto system = makeHbSystem(s.model, condensed, options.linear_algebra);
    s.result = solver.solve(*system, Eigen::VectorXd::Zero(system->size()), options);
    s.full = system->fullCoefficients(s.result.solution);
    seconds += s.result.seconds;
    s.ladder.push_back({s.model.basis.count(), s.model.samples, s.result.converged(), 0.0, false, s.result.seconds});
    if (!s.result.converged()) {
      s.failure = "the solve at H = " + std::to_string(start_harmonics) + " did not converge (" +
                  terminationName(s.result.termination) + ")";
      live[k] = false;
    }
  }
  for (int h = start_harmonics;; h *= 2) {
    if (liveCount() == 0) return finish(0);
    if (2 * h > max_harmonics) {
      for (size_t k = 0; k < count; ++k)
        if (live[k])
          state[k].failure = "the error estimate at H = " + std::to_string(h) +
                             " needs a solve at 2H, above max_harmonics = " + std::to_string(max_harmonics);
      return finish(std::find(live.begin(), live.end(), true) - live.begin());
    }
    size_t best = count;
    for (size_t k = 0; k < count; ++k) {
      if (!live[k]) continue;
      AccuracyChoice& s = state[k];
      s.estimate = estimateError(s.model, s.full, solver, options, condensed);
      seconds += s.estimate.refined.seconds;
      s.ladder.back().estimate = s.estimate.max_abs;
      s.ladder.back().estimated = true;
      s.ladder.push_back({s.estimate.refined_harmonics, s.estimate.refined_samples, s.estimate.available, 0.0, false,
                          s.estimate.refined.seconds});
      if (!s.estimate.available) {
        s.failure = "the solve at H = " + std::to_string(2 * h) + " (the error estimate at H = " + std::to_string(h) +
                    ") did not converge (" + terminationName(s.estimate.refined.termination) + ")";
        live[k] = false;
        continue;
      }
      if (best == count || s.estimate.max_abs < state[best].estimate.max_abs) best = k;
    }
    if (best == count) return finish(0);
    if (state[best].estimate.max_abs <= tolerance) {
      state[best].reached = true;
      return finish(best);
    }
    if (4 * h > max_harmonics) {
      // The reported solution stays the last one with an estimate.
      state[best].failure = "estimate " + formatNumber(state[best].estimate.max_abs) + " at H = " +
                            std::to_string(h) + "; the next rung needs a solve at H = " + std::to_string(4 * h) +
                            ", above max_harmonics = " + std::to_string(max_harmonics);
      return finish(best);
    }
    for (size_t k = 0; k < count; ++k) {
      if (!live[k]) continue;
      AccuracyChoice& s = state[k];
      if (h >= kPruneFromHarmonics && s.estimate.max_abs > kPruneFactor * state[best].estimate.max_abs) {
        live[k] = false;
        s.failure = "dropped at H = " + std::to_string(h) + ": estimate " + formatNumber(s.estimate.max_abs) +
                    " > " + formatNumber(kPruneFactor) + " x the best";
        continue;
      }
      // The refined solution is the next candidate.
      s.model = withHarmonics(s.model, s.estimate.refined_harmonics);
      s.full = s.estimate.refined_full;
      s.result = s.estimate.refined;
    }
  }
}

AccuracyChoice refineToAccuracy(const HbModel& model, const Eigen::VectorXd& full, const SolverResult& result,
                                double tolerance, int max_harmonics, Solver& solver, const SolverOptions& options,
                                bool condensed) {
  checkLadderArguments(tolerance, model.basis.count(), max_harmonics);
  AccuracyChoice out;
  out.model = model;
  out.full = full;
  out.result = result;
  // The given solve is not counted in `seconds`: it belongs to the caller.
  out.ladder.push_back({model.basis.count(), model.samples, result.converged(), 0.0, false, result.seconds});
  if (!result.converged()) {
    out.failure = "the solve at H = " + std::to_string(model.basis.count()) + " did not converge (" +
                  terminationName(result.termination) + ")";
    return out;
  }
  climbLadder(tolerance, max_harmonics, solver, options, condensed, out);
  return out;
}

}  // namespace eqhb
