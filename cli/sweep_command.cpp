#include "sweep_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include "eqhb/accuracy/accuracy_sweep.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/harmonic_balance/problem_scales.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/output/curve_json.h"
#include "eqhb/output/curve_writers.h"
#include "eqhb/stability/curve_stability.h"
#include "flag_names.h"
#include "terminal/progress.h"
#include "terminal/run_program.h"
#include "terminal/verbosity.h"

namespace eqhb::cli {

void addSweepCommand(CLI::App& app, SolveArguments& s, SweepArguments& w) {
  auto* cmd = app.add_subcommand("sweep", "Frequency-response curve by continuation in omega");
  addSceneOptions(cmd, s.scene);
  addSolverOptions(cmd, s);
  cmd->add_option("--from", w.from, "Start frequency (default: the scene's sweep.from)");
  cmd->add_option("--to", w.to, "End frequency (default: the scene's sweep.to)");
  cmd->add_option("--step", w.step,
                  "Grid step in omega (sequential; default a hundredth of the range, 101 points in any unit) or "
                  "initial scaled arclength step (default 0.01)");
  cmd->add_flag("--arclength", w.arclength, "Pseudo-arclength continuation (passes turning points)");
  cmd->add_option("--min-step", w.min_step,
                  "Smallest step: in omega for the sequential sweep's halvings (default min(1e-6, step)), in "
                  "scaled arclength for --arclength; a sweep that needs less stops and says where");
  cmd->add_option("--max-step", w.max_step,
                  "Largest scaled arclength step with --arclength (default max(0.1, step); 0.1 is a tenth of the "
                  "range in omega or a 10 % change of the response)");
  cmd->add_option("--max-points", w.max_points, "Most points on the curve")->capture_default_str();
  cmd->add_option("--out", w.out, "Write the curve as CSV");
  cmd->add_option("--chart", w.chart, "Write a chart of the curve: PREFIX.png and PREFIX.svg (matplotlib)");
  cmd->add_flag("--log-amplitude", w.log_amplitude, "Chart: logarithmic amplitude axis");
  addStabilityFlag(cmd, s);
  cmd->add_flag("--error-estimate", s.accuracy.error_estimate,
                "Per converged point, the estimated relative error of max|x| by one more solve at 2H "
                "(error_estimate column and JSON key)");
  cmd->add_option("--accuracy", s.accuracy.tolerance,
                  "Every point with an estimated relative error of max|x| <= TOL: H chosen at the first point "
                  "(doubling from --harmonics or 5), then raised on the points whose estimate exceeds TOL");
  cmd->add_option("--max-harmonics", s.accuracy.max_harmonics, "With --accuracy: the largest H solved")
      ->capture_default_str();
  cmd->add_flag("--json", w.json,
                "Print the curve as one JSON object: settings, stop reason, folds, and per point the counts, "
                "amplitudes and Fourier coefficients of every DOF and law force");
}

int runSweep(const SolveArguments& s, const SweepArguments& w) {
  const Scene scene = loadSceneWith(s.scene);
  ContinuationOptions options;
  if (!w.from && !scene.sweep_from) throwInputError("--from", "(missing)", "the scene has no [sweep]: give --from and --to");
  if (!w.to && !scene.sweep_to) throwInputError("--to", "(missing)", "the scene has no [sweep]: give --from and --to");
  options.from = w.from ? *w.from : *scene.sweep_from;
  options.to = w.to ? *w.to : *scene.sweep_to;
  if (!(options.from > 0.0) || !std::isfinite(options.from))
    throwInputError("--from", formatNumber(options.from), "must be finite and > 0");
  if (!(options.to > 0.0) || !std::isfinite(options.to))
    throwInputError("--to", formatNumber(options.to), "must be finite and > 0");
  if (options.from == options.to)
    throwInputError("--to", formatNumber(options.to), "must differ from --from: the range has zero width");
  auto positive = [](const char* name, double value) {
    if (!(value > 0.0) || !std::isfinite(value)) throwInputError(name, formatNumber(value), "must be finite and > 0");
  };
  const double step = w.step ? *w.step : ContinuationOptions::defaultStep(options.from, options.to, w.arclength);
  positive("--step", step);
  if (w.min_step) positive("--min-step", *w.min_step);
  if (w.max_step) positive("--max-step", *w.max_step);
  options.step = step;
  options.min_step = w.min_step ? *w.min_step : ContinuationOptions::defaultMinStep(step);
  options.max_step = w.max_step ? *w.max_step : ContinuationOptions::defaultMaxStep(step);
  if (options.min_step > options.max_step)
    throwInputError(w.min_step ? "--min-step" : "--max-step",
                    formatNumber(w.min_step ? options.min_step : options.max_step),
                    "--min-step = " + formatNumber(options.min_step) + " must be <= --max-step = " +
                        formatNumber(options.max_step));
  options.max_points = w.max_points;
  options.condensed = !s.full;
  // Every option checked before any count is derived from them.
  if (w.arclength) options.validate();
  else options.validateGrid();
  const SolverOptions solver_options = solverOptions(s);
  const bool with_accuracy = s.accuracy.tolerance.has_value();
  if (with_accuracy && s.stability)
    throwInputError("--stability", "(set)", "not with --accuracy: the points of such a curve differ in H");
  auto solver = makeSolver(s.solver);
  const OwnedFallbackChain fallbacks(s.fallback, s.solver, "--fallback");
  options.fallbacks = fallbacks.chain();
  const int dofs = scene.model.structure.dofs();
  const int expected = w.arclength ? 0 : static_cast<int>(options.gridPoints());
  ProgressLine line(verbosity().progress, scene.name + " sweep");
  const bool verbose = verbosity().verbose;
  if (verbose)
    std::cerr << "eqhb: sweep " << scene.source << ": omega " << options.from << " -> " << options.to << ", "
              << (w.arclength ? "arclength" : "sequential") << ", step " << options.step << ", "
              << solver->name() << ", H = " << scene.model.basis.count() << ", N = " << scene.model.samples
              << ", " << (options.condensed ? "condensed" : "full") << " system\n";
  int failed = 0;
  Progress progress = [&](const CurvePoint& p, int index) {
    if (!p.converged) ++failed;
    if (verbose) {
      std::ostringstream text;
      text << "eqhb: point " << index + 1 << " omega = " << p.omega << ": " << p.termination << ", "
           << p.iterations << " iterations, |g| = " << p.residual_norm << ", " << p.seconds << " s";
      line.message(text.str());
    }
    // The ETA follows the distance covered in omega (exact on a grid, an
    // estimate along an arclength curve that may turn back).
    const double fraction = std::clamp((p.omega - options.from) / (options.to - options.from), 0.0, 1.0);
    char detail[96];
    std::snprintf(detail, sizeof detail, "omega = %.5f  max|x%d| = %.5g%s", p.omega, dofs,
                  p.converged ? p.max_abs[dofs - 1] : NAN, failed ? ("  " + std::to_string(failed) + " failed").c_str() : "");
    line.update(fraction, "point " + std::to_string(index + 1) + (expected ? "/" + std::to_string(expected) : ""),
                detail);
  };
  std::optional<AccurateCurve> accurate;
  RhoCandidates rho;
  Curve curve;
  if (with_accuracy) {
    const int start = s.scene.harmonics ? *s.scene.harmonics : std::min(5, scene.model.basis.count());
    Progress checked = [&](const CurvePoint& p, int index) {
      if (verbose)
        line.message("eqhb: point " + std::to_string(index + 1) + " omega = " + formatNumber(p.omega) + ": H = " +
                     std::to_string(p.harmonics) + ", estimate " + formatNumber(p.error_estimate.value_or(NAN)) +
                     (p.accuracy && p.accuracy->met ? "" : " (NOT met)"));
    };
    rho = rhoCandidates(s.scene);
    accurate = sweepToAccuracy(rho.models, *s.accuracy.tolerance, start, s.accuracy.max_harmonics, *solver,
                               solver_options, options, w.arclength, progress, checked);
    curve = accurate->curve;
  } else {
    curve = w.arclength ? sweepArclength(scene.model, *solver, solver_options, options, progress)
                        : sweepSequential(scene.model, *solver, solver_options, options, progress);
  }
  const HbModel& curve_model = accurate ? accurate->model : scene.model;
  line.finish(std::to_string(curve.points.size()) + " points, " + std::to_string(curve.failed_points) + " failed");
  if (s.accuracy.error_estimate && !accurate)
    estimateCurveErrors(scene.model, *solver, solver_options, options.condensed, &curve);
  std::optional<CurveStability> stability;
  if (s.stability) stability = analyseCurveStability(scene.model, curve);

  CurveRun run;
  run.scene = scene.name;
  run.solver = solver->name();
  run.arclength = w.arclength;
  run.from = options.from;
  run.to = options.to;
  run.step = options.step;
  run.condensed = options.condensed;
  run.model = &curve_model;
  run.stability = stability ? &*stability : nullptr;
  if (!curve.complete) run.advice = rhoScaleAdvice(curve_model);
  run.error_estimate = s.accuracy.error_estimate;
  if (accurate) {
    double worst = 0.0;
    for (const auto& p : curve.points)
      if (p.converged && p.error_estimate) worst = std::max(worst, *p.error_estimate);
    std::ostringstream line;
    line << "--accuracy " << accurate->tolerance << ": H = " << curve_model.basis.count()
         << ", rho = " << rhoJson(rho.scene_rho, rho.factors[accurate->first.candidate]).dump()
         << " chosen at omega = " << options.from << ", raised up to H = " << accurate->highest_harmonics
         << "; largest estimate " << worst << "; not met at " << accurate->not_met.size() << " point(s); "
         << accurate->seconds << " s in all";
    run.accuracy = line.str();
  }
  if (w.json) {
    nlohmann::json out = curveJson(curve, run);
    if (accurate) {
      out["rho"] = rhoJson(rho.scene_rho, rho.factors[accurate->first.candidate]);
      out["accuracy"] = {{"tolerance", accurate->tolerance},
                         {"reached", accurate->not_met.empty() && curve.failed_points == 0 && curve.complete},
                         {"not_met", accurate->not_met},
                         {"highest_harmonics", accurate->highest_harmonics},
                         {"seconds", accurate->seconds},
                         {"first_point", accuracyJson(accurate->first, accurate->tolerance, rho.factors)}};
    }
    std::cout << out.dump(2) << "\n";
  }
  // With --json, stdout is the JSON object alone; the summary goes to stderr.
  writeCurveSummary(w.json ? std::cerr : std::cout, curve, run);
  if (!w.out.empty()) writeCurveCsv(w.out, curve, dofs);
  if (!w.chart.empty()) {
    const std::string csv = w.out.empty() ? w.chart + ".csv" : w.out;
    if (w.out.empty()) writeCurveCsv(csv, curve, dofs);
    std::vector<std::string> command = {python3(), findDataFile("plot_curve.py"), csv, w.chart, scene.name};
    if (w.log_amplitude) command.push_back("--log-amplitude");
    if (runProgram(command) != 0)
      throw std::runtime_error("--chart: plotting failed (needs " + command[0] + " with matplotlib)");
  }
  if (accurate && !accurate->not_met.empty()) {
    std::ostringstream where;
    for (size_t i = 0; i < accurate->not_met.size() && i < 10; ++i) where << (i ? ", " : "") << accurate->not_met[i];
    if (accurate->not_met.size() > 10) where << ", ... (" << accurate->not_met.size() << " points)";
    const CurvePoint* first_miss = nullptr;
    for (const auto& p : curve.points)
      if (p.accuracy && !p.accuracy->met) {
        first_miss = &p;
        break;
      }
    std::cerr << "eqhb: --accuracy " << accurate->tolerance << " not met at omega = " << where.str();
    if (first_miss) std::cerr << " (at omega = " << first_miss->omega << ": " << withFlagNames(first_miss->accuracy->failure) << ")";
    std::cerr << "\n";
    return 1;
  }
  return curve.complete && curve.failed_points == 0 && !curve.points.empty() ? 0 : 1;
}

}  // namespace eqhb::cli
