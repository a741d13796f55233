#include "sweep_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "eqhb/app/sweep.h"
#include "eqhb/error.h"
#include "eqhb/curves/curve_writers.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/output/sweep_output.h"
#include "eqhb/scenes/dof_choice.h"
#include "flag_names.h"
#include "hdf5_option.h"
#include "terminal/progress.h"
#include "terminal/run_program.h"
#include "terminal/stop_signals.h"
#include "terminal/verbosity.h"

namespace eqhb::cli {

void addSweepCommand(CLI::App& app, SolveArguments& s, SweepArguments& w) {
  auto* cmd = app.add_subcommand("sweep", "Frequency-response curve by continuation in omega");
  addSceneOptions(cmd, s.scene);
  addSolverOptions(cmd, s);
  cmd->add_option("--from", w.curve.from, "Start frequency (default: the scene's sweep.from)");
  cmd->add_option("--to", w.curve.to, "End frequency (default: the scene's sweep.to)");
  cmd->add_option("--step", w.curve.step,
                  "Grid step in omega (sequential; default a hundredth of the range, 101 points in any unit) or "
                  "initial scaled arclength step (default 0.01)");
  cmd->add_flag("--arclength", w.curve.arclength, "Pseudo-arclength continuation (passes turning points)");
  cmd->add_option("--min-step", w.curve.min_step,
                  "Smallest step: in omega for the sequential sweep's halvings (default min(1e-6, step)), in "
                  "scaled arclength for --arclength; a sweep that needs less stops and says where");
  cmd->add_option("--max-step", w.curve.max_step,
                  "Largest scaled arclength step with --arclength (default max(0.1, step); 0.1 is a tenth of the "
                  "range in omega or a 10 % change of the response)");
  cmd->add_option("--max-points", w.curve.max_points, "Most points on the curve")->capture_default_str();
  cmd->add_option("--curve-time-limit", w.curve.curve_time_limit,
                  "Seconds for the whole sweep (0 = none): the curve stops between two points and writes those "
                  "found, not complete (exit 1); stability gets what is left. SIGINT or SIGTERM stop it the same "
                  "way (a second signal at once)")
      ->capture_default_str();
  cmd->add_option("--out", w.out, "Write the curve as CSV");
  cmd->add_option("--chart", w.chart, "Write a chart of the curve: PREFIX.png and PREFIX.svg (matplotlib)");
  addHdf5Option(cmd, w.hdf5, "the curve");
  cmd->add_flag("--log-amplitude", w.log_amplitude, "Chart: logarithmic amplitude axis");
  addStabilityFlag(cmd, s);
  cmd->add_flag("--error-estimate", s.accuracy.error_estimate,
                "Per converged point, the estimated relative error of max|x| by one more solve at 2H "
                "(error_estimate column and JSON key)");
  cmd->add_option("--accuracy", s.accuracy.tolerance,
                  "Every point with a relative error of max|x| <= TOL (--accuracy-test): H chosen at the first point "
                  "(doubling from --harmonics or 5), then raised on the points whose test fails");
  cmd->add_option("--max-harmonics", s.accuracy.max_harmonics, "With --accuracy: the largest H solved")
      ->capture_default_str();
  addAccuracyTestOption(cmd, s.accuracy);
  cmd->add_flag("--json", w.json,
                "Print the curve as one JSON object: settings, stop reason, folds, and per point the counts, "
                "amplitudes and Fourier coefficients of every DOF and law force");
}

namespace {

app::SweepOptions sweepOptions(const SolveArguments& s, const SweepArguments& w) {
  app::SweepOptions o = w.curve;
  readSolverChoice(s, &o);
  readSolutionChecks(s, &o);
  return o;
}

// The progress line (and with --verbose a line per point) as the sweep runs.
class SweepProgress {
 public:
  explicit SweepProgress(const app::SweepPlan& plan)
      : plan_(plan), line_(verbosity().progress, plan.scene.name + " sweep"), verbose_(verbosity().verbose) {
    const ContinuationOptions& c = plan.continuation;
    if (verbose_)
      std::cerr << "eqhb: sweep " << plan.scene.source << ": omega " << c.from << " -> " << c.to << ", "
                << (plan.options.arclength ? "arclength" : "sequential") << ", step " << c.step << ", "
                << plan.solver_name << ", H = " << plan.scene.model.basis.count() << ", N = "
                << plan.scene.model.samples << ", " << (c.condensed ? "condensed" : "full") << " system\n";
  }
  app::SweepCallbacks callbacks() {
    app::SweepCallbacks out;
    out.point = [this](const CurvePoint& p, int index) { point(p, index); };
    out.checked = [this](const CurvePoint& p, int index) { checked(p, index); };
    out.stability = [this](int done, int total) {
      line_.update(total > 0 ? static_cast<double>(done) / total : -1.0,
                   "stability " + std::to_string(done) + "/" + std::to_string(total));
    };
    return out;
  }
  void finish(const Curve& curve) {
    line_.finish(std::to_string(curve.points.size()) + " points, " + std::to_string(curve.failed_points) + " failed");
  }

 private:
  void point(const CurvePoint& p, int index) {
    if (!p.converged) ++failed_;
    if (verbose_) {
      std::ostringstream text;
      text << "eqhb: point " << index + 1 << " omega = " << p.omega << ": " << p.termination << ", "
           << p.iterations << " iterations, |g| = " << p.residual_norm << ", " << p.seconds << " s";
      line_.message(text.str());
    }
    // The ETA follows the distance covered in omega (exact on a grid, an
    // estimate along an arclength curve that may turn back).
    const ContinuationOptions& c = plan_.continuation;
    const double fraction = std::clamp((p.omega - c.from) / (c.to - c.from), 0.0, 1.0);
    const int peak = plan_.scene.output.peak;
    const int expected = plan_.expectedPoints();
    char detail[96];
    std::snprintf(detail, sizeof detail, "omega = %.5f  max|%s| = %.5g%s", p.omega,
                  dofLabel(plan_.scene.model, peak).c_str(), p.converged ? p.max_abs[peak] : NAN,
                  failed_ ? ("  " + std::to_string(failed_) + " failed").c_str() : "");
    line_.update(fraction, "point " + std::to_string(index + 1) + (expected ? "/" + std::to_string(expected) : ""),
                 detail);
  }
  void checked(const CurvePoint& p, int index) {
    if (verbose_)
      line_.message("eqhb: point " + std::to_string(index + 1) + " omega = " + formatNumber(p.omega) + ": H = " +
                    std::to_string(p.harmonics) + ", estimate " + formatNumber(p.error_estimate.value_or(NAN)) +
                    (p.accuracy && p.accuracy->met ? "" : " (NOT met)"));
  }

  const app::SweepPlan& plan_;
  ProgressLine line_;
  bool verbose_;
  int failed_ = 0;
};

void writeChart(const SweepArguments& w, const app::SweepResult& r) {
  const std::string csv = w.out.empty() ? w.chart + ".csv" : w.out;
  if (w.out.empty()) output::writeSweepCsv(csv, r);
  std::vector<std::string> command = {python3(), findDataFile("plot_curve.py"), csv, w.chart, r.plan.scene.name};
  if (w.log_amplitude) command.push_back("--log-amplitude");
  if (runProgram(command) != 0)
    throw std::runtime_error("--chart: plotting failed (needs " + command[0] + " with matplotlib)");
}

// Where an accuracy target was not met, on stderr.
void reportAccuracyNotMet(const app::SweepResult& r) {
  const AccurateCurve& a = *r.accurate;
  std::ostringstream where;
  for (size_t i = 0; i < a.not_met.size() && i < 10; ++i) where << (i ? ", " : "") << a.not_met[i];
  if (a.not_met.size() > 10) where << ", ... (" << a.not_met.size() << " points)";
  const CurvePoint* first_miss = nullptr;
  for (const auto& p : r.curve.points)
    if (p.accuracy && !p.accuracy->met) {
      first_miss = &p;
      break;
    }
  std::cerr << "eqhb: --accuracy " << a.tolerance << " not met at omega = " << where.str();
  if (first_miss)
    std::cerr << " (at omega = " << first_miss->omega << ": " << withFlagNames(first_miss->accuracy->failure) << ")";
  std::cerr << "\n";
}

}  // namespace

int runSweep(const SolveArguments& s, const SweepArguments& w) {
  const StopOnSignals signals;
  app::SweepOptions options = sweepOptions(s, w);
  options.stop_requested = signals.requested();
  const app::SweepPlan plan = app::planSweep(s.scene, options);
  SweepProgress progress(plan);
  app::SweepResult r = app::sweep(plan, progress.callbacks());
  progress.finish(r.curve);
  r.curve.stop_reason = withFlagNames(r.curve.stop_reason);  // the library names options, the command flags
  const CurveRun run = output::curveRun(r, "--accuracy");
  if (w.json) std::cout << output::sweepJson(r).dump(2) << "\n";
  // With --json, stdout is the JSON object alone; the summary goes to stderr.
  writeCurveSummary(w.json ? std::cerr : std::cout, r.curve, run);
  if (!w.out.empty()) output::writeSweepCsv(w.out, r);
  if (!w.chart.empty()) writeChart(w, r);
  if (!w.out.empty() || !w.chart.empty())
    if (const std::string note = shownDofsNote(r.plan.scene.model, r.plan.scene.output); !note.empty())
      (w.json ? std::cerr : std::cout) << "  " << (w.out.empty() ? "chart" : w.chart.empty() ? "CSV" : "CSV and chart")
                                       << ": " << note << "\n";
  if (!w.hdf5.empty()) writeSweepHdf5File(w.hdf5, r);
  if (r.accurate && !r.accurate->not_met.empty()) reportAccuracyNotMet(r);
  return r.succeeded() ? 0 : 1;
}

}  // namespace eqhb::cli
