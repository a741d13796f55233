#include "eqhb/accuracy/accuracy_target.h"

#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

AccuracyChoice chooseHarmonics(const HbModel& scene_model, double tolerance, int start_harmonics, int max_harmonics,
                               Solver& solver, const SolverOptions& options, bool condensed) {
  if (!std::isfinite(tolerance) || tolerance <= 0.0 || tolerance >= 1.0)
    throwInputError("--accuracy", formatNumber(tolerance), "must be a relative error in (0, 1)");
  if (max_harmonics < 1 || max_harmonics > 100000)
    throwInputError("--max-harmonics", std::to_string(max_harmonics), "must be in [1, 100000]");
  if (start_harmonics < 1 || start_harmonics > max_harmonics)
    throwInputError("--harmonics", std::to_string(start_harmonics),
                    "the first H tried must be in [1, --max-harmonics = " + std::to_string(max_harmonics) + "]");
  AccuracyChoice out;
  out.model = withHarmonics(scene_model, start_harmonics);
  {
    auto system = makeHbSystem(out.model, condensed, options.linear_algebra);
    out.result = solver.solve(*system, Eigen::VectorXd::Zero(system->size()), options);
    out.full = system->fullCoefficients(out.result.solution);
  }
  out.seconds += out.result.seconds;
  out.ladder.push_back({out.model.basis.count(), out.model.samples, out.result.converged(), 0.0, false,
                        out.result.seconds});
  if (!out.result.converged()) {
    out.failure = "the solve at H = " + std::to_string(start_harmonics) + " did not converge (" +
                  terminationName(out.result.termination) + ")";
    return out;
  }
  if (2 * start_harmonics > max_harmonics) {
    out.failure = "the error estimate at H = " + std::to_string(start_harmonics) +
                  " needs a solve at 2H, above --max-harmonics = " + std::to_string(max_harmonics);
    return out;
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
      return out;
    }
    if (out.estimate.max_abs <= tolerance) {
      out.reached = true;
      return out;
    }
    if (4 * h > max_harmonics) {
      // The reported solution stays the last one with an estimate.
      out.failure = "estimate " + formatNumber(out.estimate.max_abs) + " at H = " + std::to_string(h) +
                    "; the next rung needs a solve at H = " + std::to_string(4 * h) + ", above --max-harmonics = " +
                    std::to_string(max_harmonics);
      return out;
    }
    // The refined solution is the next candidate.
    out.model = withHarmonics(out.model, out.estimate.refined_harmonics);
    out.full = out.estimate.refined_full;
    out.result = out.estimate.refined;
  }
}

}  // namespace eqhb
