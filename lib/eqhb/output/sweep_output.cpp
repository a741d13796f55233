#include "eqhb/output/sweep_output.h"

#include <algorithm>
#include <sstream>

#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/problem_scales.h"
#include "eqhb/output/curve_json.h"
#include "eqhb/output/solution_json.h"
#include "eqhb/scenes/dof_choice.h"

namespace eqhb::output {

namespace {

double chosenRhoFactor(const app::SweepResult& r) { return r.rho.factors[r.accurate->first.candidate]; }

// How the points of an accuracy target's curve were tested: the count per
// test (rung_test.h) and the largest tested error.
struct PointTests {
  int exact = 0, estimate = 0;
  double largest = 0.0;
};
PointTests pointTests(const Curve& curve) {
  PointTests t;
  for (const CurvePoint& p : curve.points) {
    if (!p.accuracy || p.accuracy->test.empty()) continue;
    (p.accuracy->test == accuracyTestName(AccuracyTest::kExactOrbit) ? t.exact : t.estimate) += 1;
    t.largest = std::max(t.largest, p.accuracy->error);
  }
  return t;
}

// The summary's accuracy line: the choice at the first point, how far H was
// raised, how the points were tested, and where the target was not met.
std::string accuracyLine(const app::SweepResult& r, const std::string& option) {
  const AccurateCurve& a = *r.accurate;
  const PointTests tests = pointTests(r.curve);
  std::ostringstream line;
  line << option << " " << a.tolerance << ": H = " << r.model.basis.count()
       << ", rho = " << rhoJson(r.rho.scene_rho, chosenRhoFactor(r)).dump() << " chosen at omega = "
       << r.plan.continuation.from << ", raised up to H = " << a.highest_harmonics << "; tested against the exact orbit at "
       << tests.exact << " point(s), by the estimate x " << kEstimateSafetyFactor << " at " << tests.estimate
       << "; largest tested error " << tests.largest << "; not met at " << a.not_met.size() << " point(s); "
       << a.seconds << " s in all";
  return line.str();
}

}  // namespace

CurveRun curveRun(const app::SweepResult& r, const std::string& accuracy_option) {
  CurveRun run;
  run.scene = r.plan.scene.name;
  run.solver = r.plan.solver_name;
  run.arclength = r.plan.options.arclength;
  run.from = r.plan.continuation.from;
  run.to = r.plan.continuation.to;
  run.step = r.plan.continuation.step;
  run.condensed = r.plan.continuation.condensed;
  run.model = &r.model;
  run.stability = r.stability ? &*r.stability : nullptr;
  if (!r.curve.complete) run.advice = scaleAdvice(r.model);
  run.error_estimate = r.plan.options.error_estimate;
  if (r.accurate) run.accuracy = accuracyLine(r, accuracy_option);
  run.peak_dof = r.plan.scene.output.peak;
  return run;
}

void writeSweepCsv(const std::string& path, const app::SweepResult& r) {
  writeCurveCsv(path, r.curve, curveColumns(r.plan.scene.model, r.plan.scene.output.shown));
}

nlohmann::json sweepJson(const app::SweepResult& r) {
  nlohmann::json out = curveJson(r.curve, curveRun(r));
  const HbModel& model = r.plan.scene.model;
  out["dof_labels"] = curveColumns(model).labels;
  out["peak_dof"] = dofLabel(model, r.plan.scene.output.peak);
  out["shown"] = shownLabels(model, r.plan.scene.output);
  if (!r.accurate) return out;
  const AccurateCurve& a = *r.accurate;
  out["rho"] = rhoJson(r.rho.scene_rho, chosenRhoFactor(r));
  out["accuracy"] = {{"tolerance", a.tolerance},
                     {"reached", a.not_met.empty() && r.curve.failed_points == 0 && r.curve.complete},
                     {"not_met", a.not_met},
                     {"highest_harmonics", a.highest_harmonics},
                     {"seconds", a.seconds},
                     {"tested_exact_orbit", pointTests(r.curve).exact},
                     {"tested_estimate", pointTests(r.curve).estimate},
                     {"largest_error", pointTests(r.curve).largest},
                     {"first_point", accuracyJson(a.first, a.tolerance, r.rho.factors)}};
  return out;
}

}  // namespace eqhb::output
