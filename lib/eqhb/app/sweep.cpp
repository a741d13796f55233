#include "eqhb/app/sweep.h"

#include <algorithm>
#include <cmath>

#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/preload/operating_point.h"
#include "eqhb/solvers/option_check.h"

namespace eqhb::app {

namespace {

bool positive(double value) { return value > 0.0 && std::isfinite(value); }

// The range from the options, else from the scene's [sweep].
void resolveRange(const Scene& scene, const SweepOptions& o, ContinuationOptions* c) {
  if (!o.from && !scene.sweep_from) throwInputError("from", "(missing)", "the scene has no [sweep]: give from and to");
  if (!o.to && !scene.sweep_to) throwInputError("to", "(missing)", "the scene has no [sweep]: give from and to");
  c->from = o.from ? *o.from : *scene.sweep_from;
  c->to = o.to ? *o.to : *scene.sweep_to;
  if (!positive(c->from)) throwInputError("from", formatNumber(c->from), "must be finite and > 0");
  if (!positive(c->to)) throwInputError("to", formatNumber(c->to), "must be finite and > 0");
  if (c->from == c->to) throwInputError("to", formatNumber(c->to), "must differ from from: the range has zero width");
}

// The steps from the options, else ContinuationOptions' defaults.
void resolveSteps(const SweepOptions& o, ContinuationOptions* c) {
  c->step = o.step ? *o.step : ContinuationOptions::defaultStep(c->from, c->to, o.arclength);
  if (!positive(c->step)) throwInputError("step", formatNumber(c->step), "must be finite and > 0");
  c->min_step = o.min_step ? *o.min_step : ContinuationOptions::defaultMinStep(c->step);
  c->max_step = o.max_step ? *o.max_step : ContinuationOptions::defaultMaxStep(c->step);
  if (c->min_step > c->max_step)
    throwInputError(o.min_step ? "min_step" : "max_step", formatNumber(o.min_step ? c->min_step : c->max_step),
                    "min_step = " + formatNumber(c->min_step) + " must be <= max_step = " + formatNumber(c->max_step));
}

// The stability's own limit (0: none) within what is left of the sweep's:
// a sweep out of time gets the smallest limit, which stops before the first
// point and says so (stability_time_limited).
double withinCurveLimit(double stability_limit, const Deadline& sweep) {
  if (!sweep.limited()) return stability_limit;
  const double left = std::max(sweep.remaining(), 1e-9);
  return stability_limit > 0.0 ? std::min(stability_limit, left) : left;
}

}  // namespace

bool SweepOptions::isValid(std::string* why) const {
  if (solver.empty()) return refuseOption(why, "solver", "\"\"", "must name a backend (see solvers)");
  if (step && !positive(*step)) return refuseOption(why, "step", formatNumber(*step), "must be finite and > 0");
  if (min_step && !positive(*min_step))
    return refuseOption(why, "min_step", formatNumber(*min_step), "must be finite and > 0");
  if (max_step && !positive(*max_step))
    return refuseOption(why, "max_step", formatNumber(*max_step), "must be finite and > 0");
  if (!(curve_time_limit >= 0.0) || !std::isfinite(curve_time_limit))
    return refuseOption(why, "curve_time_limit", formatNumber(curve_time_limit), "must be finite and >= 0 (0: none)");
  if (!SolutionChecks::isValid(why)) return false;
  if (accuracy && stability)
    return refuseOption(why, "stability", "(set)", "not with accuracy: the points of such a curve differ in H");
  return solver_options.isValid(why);
}

int SweepPlan::expectedPoints() const {
  return options.arclength ? 0 : static_cast<int>(continuation.gridPoints());
}

SweepPlan planSweep(const SceneSettings& settings, const SweepOptions& o) {
  std::string why;
  if (!o.isValid(&why)) throw InputError(why);
  SweepPlan plan;
  plan.settings = settings;
  plan.options = o;
  plan.scene = loadScene(settings);
  ContinuationOptions& c = plan.continuation;
  resolveRange(plan.scene, o, &c);
  resolveSteps(o, &c);
  c.max_points = o.max_points;
  c.condensed = o.condensed;
  // Under a preload the first point starts from the response linearised
  // about the static state at its omega (operating_point.h).
  if (plan.scene.at_rest) {
    HbModel first = plan.scene.model;
    first.omega = c.from;
    c.start_full = linearisedStart(first, *plan.scene.at_rest, o.solver_options);
  }
  // Every option checked before any count is derived from them.
  if (o.arclength) c.validate();
  else c.validateGrid();
  const auto solver = makeSolver(o.solver);
  plan.solver_name = solver->name();
  // Options the backend refuses are input, not a point that failed: every
  // point would fail the same way (the fallback steps run other backends
  // on their own defaults and are not asked).
  checkSolverOptions(*solver, o.solver_options);
  const OwnedFallbackChain fallbacks(o.fallback, o.solver, "fallback");  // an unknown step fails here
  return plan;
}

double SweepResult::largestEstimate() const {
  double worst = 0.0;
  for (const auto& p : curve.points)
    if (p.converged && p.error_estimate) worst = std::max(worst, *p.error_estimate);
  return worst;
}

bool SweepResult::succeeded() const {
  if (accurate && !accurate->not_met.empty()) return false;
  return curve.complete && curve.failed_points == 0 && !curve.points.empty();
}

SweepResult sweep(const SweepPlan& plan, const SweepCallbacks& callbacks) {
  const SweepOptions& o = plan.options;
  const HbModel& scene_model = plan.scene.model;
  auto solver = makeSolver(o.solver);
  const OwnedFallbackChain fallbacks(o.fallback, o.solver, "fallback");
  ContinuationOptions continuation = plan.continuation;
  continuation.fallbacks = fallbacks.chain();
  continuation.stop = CurveStop{Deadline(o.curve_time_limit), o.stop_requested};
  if (plan.scene.at_rest) continuation.fallbacks.at_rest = std::make_shared<const StaticContactState>(*plan.scene.at_rest);
  SweepResult result;
  result.plan = plan;
  if (o.accuracy) {
    const int start = plan.settings.harmonics ? *plan.settings.harmonics : std::min(5, scene_model.basis.count());
    result.rho = rhoCandidates(plan.settings);
    result.accurate = sweepToAccuracy(result.rho.models, *o.accuracy, start, o.max_harmonics, *solver,
                                      o.solver_options, continuation, o.arclength, callbacks.point, callbacks.checked,
                                      AccuracyTestOptions{parseAccuracyTestChoice(o.accuracy_test)});
    result.curve = std::move(result.accurate->curve);
    result.accurate->curve = Curve{};
    result.model = result.accurate->model;
    return result;
  }
  result.curve = o.arclength
                     ? sweepArclength(scene_model, *solver, o.solver_options, continuation, callbacks.point)
                     : sweepSequential(scene_model, *solver, o.solver_options, continuation, callbacks.point);
  result.model = scene_model;
  // Stopped on request: what was found is returned as it is, at once.
  if (continuation.stop.wasRequested()) return result;
  if (o.error_estimate) estimateCurveErrors(scene_model, *solver, o.solver_options, o.condensed, &result.curve);
  if (o.stability) {
    HillOptions stability;
    stability.method = o.stability_method;
    stability.time_limit = withinCurveLimit(o.stability_time_limit, continuation.stop.deadline);
    stability.stop_requested = o.stop_requested;
    result.stability = analyseCurveStability(scene_model, result.curve, stability, callbacks.stability);
  }
  return result;
}

SweepResult sweep(const SceneSettings& scene, const SweepOptions& options, const SweepCallbacks& callbacks) {
  return sweep(planSweep(scene, options), callbacks);
}

}  // namespace eqhb::app
