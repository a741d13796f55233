#include "eqhb/output/curve_json.h"

#include "eqhb/accuracy/accuracy_sweep.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/output/solution_json.h"
#include "eqhb/output/solve_effort_json.h"

namespace eqhb {

namespace {

// The attempt at one ω: where, how the solve ended, its residual and effort;
// all that a failed point reports, and the start of a converged one.
nlohmann::json attemptJson(const CurvePoint& p) {
  nlohmann::json out = output::solveEffortJson(p);
  out["omega"] = p.omega;
  out["residual_norm"] = p.residual_norm;
  return out;
}

nlohmann::json pointJson(const CurvePoint& p, const CurveRun& run, const HillResult* hill) {
  nlohmann::json point = attemptJson(p);
  point["converged"] = p.converged;
  point["fold"] = p.fold;
  point["energy"] = p.energy;
  point["max_abs"] = p.max_abs;
  point["first_harmonic"] = p.first_harmonic;
  if (!p.fallback.empty()) point["fallback"] = p.fallback;
  if (p.error_estimate) point["error_estimate"] = *p.error_estimate;
  if (p.accuracy) {
    point["harmonics"] = p.harmonics;
    point["samples"] = p.samples;
    point["accuracy_met"] = p.accuracy->met;
    point["accuracy_seconds"] = p.accuracy->seconds;
    if (!p.accuracy->test.empty()) {
      point["accuracy_test"] = p.accuracy->test;
      point["accuracy_error"] = p.accuracy->error;
    }
    if (!p.accuracy->failure.empty()) point["accuracy_failure"] = p.accuracy->failure;
  }
  if (run.stability) {
    point["stable"] = p.stable ? nlohmann::json(*p.stable) : nlohmann::json(nullptr);
    if (!p.bifurcation.empty()) point["bifurcation"] = p.bifurcation;
    if (p.stable) {
      // The leading multipliers (largest modulus first, at most four).
      const nlohmann::json all = output::stabilityJson(*hill);
      nlohmann::json leading = nlohmann::json::array();
      for (size_t j = 0; j < all["multipliers"].size() && j < 4; ++j) leading.push_back(all["multipliers"][j]);
      point["spectral_radius"] = all["spectral_radius"];
      point["multipliers"] = leading;
      point["stability_method"] = hill->method;
      if (!hill->note.empty()) point["stability_note"] = hill->note;
    }
  }
  if (p.full.size() > 0) {
    const HbModel at = pointModel(*run.model, p);
    const nlohmann::json channels = output::channelsJson(at, summarize(at, p.full));
    point["dofs"] = channels["dofs"];
    point["laws"] = channels["laws"];
  }
  return point;
}

}  // namespace

nlohmann::json curveJson(const Curve& curve, const CurveRun& run) {
  const CurveParts parts = splitCurve(curve);
  nlohmann::json points = nlohmann::json::array(), failed = nlohmann::json::array();
  for (size_t i = 0; i < curve.points.size(); ++i) {
    const CurvePoint& p = curve.points[i];
    if (p.converged) points.push_back(pointJson(p, run, run.stability ? &run.stability->points[i] : nullptr));
    else failed.push_back(attemptJson(p));
  }
  const HbModel& model = *run.model;
  nlohmann::json out = {{"scene", run.scene},
                        {"solver", run.solver},
                        {"method", run.arclength ? "arclength" : "sequential"},
                        {"from", run.from},
                        {"to", run.to},
                        {"step", run.step},
                        {"system", run.condensed ? "condensed" : "full"},
                        {"harmonics", model.basis.count()},
                        {"harmonic_set", HarmonicSet::kindName(model.basis.kind())},
                        {"samples", model.samples},
                        {"complete", curve.complete},
                        {"stop_reason", curve.stop_reason},
                        {"folds", curve.fold_omegas},
                        {"failed_points", curve.failed_points},
                        {"seconds", curve.seconds},
                        {"points", points},
                        {"failed", failed}};
  if (run.stability) {
    nlohmann::json bifurcations = nlohmann::json::array();
    for (const auto& b : run.stability->bifurcations)
      bifurcations.push_back({{"omega", b.omega}, {"kind", b.kind}, {"point", parts.curve_index[b.point]}});
    out["bifurcations"] = bifurcations;
    out["stability_seconds"] = run.stability->seconds;
    out["solve_seconds"] = run.stability->solve_seconds;
    out["stability_time_limited"] = run.stability->time_limited;
    out["stability_points_analysed"] = run.stability->analysed;
  }
  return out;
}

}  // namespace eqhb
