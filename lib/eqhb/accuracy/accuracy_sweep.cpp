#include "eqhb/accuracy/accuracy_sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "eqhb/error.h"

namespace eqhb {

HbModel pointModel(const HbModel& curve_model, const CurvePoint& point) {
  HbModel m = curve_model;
  m.omega = point.omega;
  // The same chain of withHarmonics as the ladder, so that N matches.
  while (point.harmonics > m.basis.count()) m = withHarmonics(m, 2 * m.basis.count());
  return m;
}

void estimateCurveErrors(const HbModel& model, Solver& solver, const SolverOptions& options, bool condensed,
                         Curve* curve) {
  for (CurvePoint& p : curve->points) {
    if (!p.converged) continue;
    HbModel at = model;
    at.omega = p.omega;
    const ErrorEstimate e = estimateError(at, p.full, solver, options, condensed);
    if (e.available) p.error_estimate = e.max_abs;
    else p.error_estimate.reset();
  }
}

namespace {

// The point as the ladder left it: the chosen solution's description, the
// sweep's counts, the ladder's time.
void takeChoice(const AccuracyChoice& c, double tolerance, CurvePoint* p) {
  describeInto(c.model, c.full, p);
  p->converged = true;
  p->harmonics = c.model.basis.count();
  p->samples = c.model.samples;
  const bool estimated = c.estimate.refined_harmonics > 0 && c.estimate.available;
  if (estimated) p->error_estimate = c.estimate.max_abs;
  else p->error_estimate.reset();
  p->accuracy = PointAccuracy{c.reached && c.error <= tolerance, c.failure, c.seconds,
                              c.tested() ? accuracyTestName(c.test) : "", c.error};
}

}  // namespace

AccurateCurve sweepToAccuracy(const std::vector<HbModel>& candidates, double tolerance, int start_harmonics, int max_harmonics,
                              Solver& solver, const SolverOptions& solver_options,
                              const ContinuationOptions& options, bool arclength, const Progress& sweep_progress,
                              const Progress& check_progress, const AccuracyTestOptions& test) {
  const auto start = std::chrono::steady_clock::now();
  if (arclength) options.validate();
  else options.validateGrid();
  AccurateCurve out;
  out.tolerance = tolerance;
  std::vector<HbModel> at_first = candidates;
  for (HbModel& m : at_first) m.omega = options.from;
  out.first = chooseDiscretisation(at_first, tolerance, start_harmonics, max_harmonics, solver, solver_options,
                                   options.condensed, test, options.fallbacks);
  // Not reached at the first frequency: the curve runs on the last rung with
  // an estimate (or the first H if even that failed) and its points say so.
  out.model = out.first.model;
  out.model.omega = candidates.front().omega;
  // The curve starts from the first ladder's solution: a cold start on its H
  // may fail where the ladder, warm from rung to rung, converged (friction-1d
  // at ω = 0.1 with ρ = 0.01 on H = 20).
  ContinuationOptions seeded = options;
  if (out.first.result.converged()) seeded.start_full = out.first.full;
  out.curve = arclength ? sweepArclength(out.model, solver, solver_options, seeded, sweep_progress)
                        : sweepSequential(out.model, solver, solver_options, seeded, sweep_progress);
  for (size_t i = 0; i < out.curve.points.size(); ++i) {
    CurvePoint& p = out.curve.points[i];
    if (!p.converged) continue;
    HbModel at = out.model;
    at.omega = p.omega;
    if (i == 0 && out.first.reached && p.omega == options.from) {
      // The first point is the first ladder's choice, already checked: its
      // solution (the same problem the sweep solved again) and estimate.
      takeChoice(out.first, tolerance, &p);
    } else {
      SolverResult solved;
      solved.termination = Termination::kConverged;
      solved.seconds = p.seconds;
      const AccuracyChoice c = refineToAccuracy(at, p.full, solved, tolerance, max_harmonics, solver,
                                                solver_options, options.condensed, test, options.fallbacks);
      takeChoice(c, tolerance, &p);
    }
    if (!p.accuracy->met) out.not_met.push_back(p.omega);
    out.highest_harmonics = std::max(out.highest_harmonics, p.harmonics);
    if (check_progress) check_progress(p, static_cast<int>(i));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace eqhb
