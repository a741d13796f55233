#include "time_commands.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/output/simulation_json.h"
#include "terminal/progress.h"
#include "terminal/verbosity.h"

namespace eqhb::cli {

namespace {

void addTimeOptions(CLI::App* cmd, TimeArguments& t) {
  // Defaults shown are the general ones; a scene's [time_reference] replaces them.
  t.step = cmd->add_option("--step", t.options.step,
                           "Time step h, adjusted to divide the period (default: the scene's [time_reference], else)")
               ->capture_default_str();
  t.periods = cmd->add_option("--periods", t.options.max_periods, "Most periods to integrate (scene's, else)")
                  ->capture_default_str();
  t.theta = cmd->add_option("--theta", t.options.theta, "θ of the Moreau–Jean scheme, in [0.5, 1] (scene's, else)")
                ->capture_default_str();
  t.periodic_tolerance =
      cmd->add_option("--periodic-tolerance", t.options.periodic_tolerance,
                      "Relative change of the period-start state that counts as periodic (scene's, else)")
          ->capture_default_str();
  cmd->add_option("--max-seconds", t.options.max_seconds,
                  "Stop integrating after this wall-clock time if not yet periodic (0: no limit; exit 1)")
      ->capture_default_str();
  cmd->add_option("--restitution", t.options.restitution, "Newton impact coefficient of contact laws")
      ->capture_default_str();
}

// Progress of the integration, one update per period: the period count
// against the most allowed, and the change against the tolerance. The ETA
// follows the change's decay over the last periods (a transient dies
// geometrically) while it decays; otherwise the periods or the wall-clock
// limit left, whichever ends the run first.
PeriodCallback periodProgress(ProgressLine& line, const TimeOptions& options) {
  if (!line.enabled()) return PeriodCallback();
  constexpr int kDecayWindow = 5;
  auto history = std::make_shared<std::vector<double>>();
  return [&line, options, history](int periods, double change) {
    history->push_back(change);
    double fraction = static_cast<double>(periods) / options.max_periods;
    if (options.max_seconds > 0.0) fraction = std::max(fraction, line.elapsedSeconds() / options.max_seconds);
    const size_t n = history->size();
    if (n > kDecayWindow && change > options.periodic_tolerance && change > 0.0) {
      const double before = (*history)[n - 1 - kDecayWindow];
      const double rate = std::log(change / before) / kDecayWindow;  // per period, < 0 while settling
      if (rate < 0.0 && std::isfinite(rate)) {
        const double left = std::log(options.periodic_tolerance / change) / rate;
        fraction = std::max(fraction, periods / (periods + left));
      }
    }
    char detail[96];
    std::snprintf(detail, sizeof detail, "change %.3g (periodic at %.3g)", change, options.periodic_tolerance);
    line.update(std::min(fraction, 1.0), "period " + std::to_string(periods) + "/" + std::to_string(options.max_periods),
                detail);
  };
}

void reportUnsettled(const TimeReference& ref, const TimeOptions& options) {
  if (ref.periodic) return;
  if (ref.timed_out)
    std::cerr << "eqhb: no periodic steady state within --max-seconds = " << options.max_seconds << " ("
              << ref.periods << " periods, change " << ref.periodicity_error << " > " << options.periodic_tolerance
              << ")\n";
  else
    std::cerr << "eqhb: no periodic steady state within " << ref.periods << " periods (change "
              << ref.periodicity_error << " > " << options.periodic_tolerance << ")\n";
}

}  // namespace

app::TimeSettings timeSettings(const TimeArguments& t) {
  auto given = [](const CLI::Option* o) { return o && o->count() > 0; };
  app::TimeSettings settings;
  if (given(t.step)) settings.step = t.options.step;
  if (given(t.theta)) settings.theta = t.options.theta;
  if (given(t.periods)) settings.periods = t.options.max_periods;
  if (given(t.periodic_tolerance)) settings.periodic_tolerance = t.options.periodic_tolerance;
  settings.max_seconds = t.options.max_seconds;
  settings.restitution = t.options.restitution;
  return settings;
}

void addSimulateCommand(CLI::App& app, SolveArguments& s, TimeArguments& t) {
  auto* cmd = app.add_subcommand("simulate", "Integrate a scene in time to its periodic steady state (reference)");
  addSceneOptions(cmd, s.scene);
  addTimeOptions(cmd, t);
  cmd->add_flag("--from-hb", t.from_hb, "Start from the harmonic-balance solution instead of rest");
  cmd->add_option("--solver", s.solver, "Backend for --from-hb");
  cmd->add_flag("--json", s.json, "Print one JSON object");
  cmd->add_flag("--trajectory", s.trajectory,
                "With --json: add the last period's samples of x, dx/dt and the law forces");
}

void addCompareCommand(CLI::App& app, SolveArguments& s, TimeArguments& t) {
  auto* cmd = app.add_subcommand("compare", "Harmonic balance against the time-domain reference, with errors");
  addSceneOptions(cmd, s.scene);
  addSolverOptions(cmd, s);
  addTimeOptions(cmd, t);
  cmd->add_flag("--from-rest", t.from_rest, "Start the reference from rest (default: from the HB solution)");
  cmd->add_flag("--json", s.json, "Print one JSON object");
}

namespace {
// The progress line of an integration, made once its options are known.
struct ProgressObserver {
  std::unique_ptr<ProgressLine> line;
  app::PeriodObserver observer(const std::string& what) {
    return [this, what](const Scene& scene, const TimeOptions& options) {
      line = std::make_unique<ProgressLine>(verbosity().progress, scene.name + " " + what);
      return periodProgress(*line, options);
    };
  }
  void finish(const TimeReference& ref) {
    if (line) line->finish(ref.periodic ? "periodic" : "NOT periodic");
  }
};

void printWarnings(const app::HbRun& run) {
  for (const std::string& w : run.warnings) std::cerr << "eqhb: warning: " << w << "\n";
}
}  // namespace

int runSimulate(const SolveArguments& s, const TimeArguments& t) {
  app::SimulateOptions options;
  options.time = timeSettings(t);
  options.from_hb = t.from_hb;
  if (t.from_hb) options.hb = solveOptions(s);
  ProgressObserver progress;
  auto observer = [&](const Scene& scene, const TimeOptions& o) {
    if (verbosity().verbose)
      std::cerr << "eqhb: simulate " << scene.source << ": h = " << o.step << ", theta = " << o.theta
                << ", at most " << o.max_periods << " periods"
                << (o.max_seconds > 0.0 ? " and " + formatNumber(o.max_seconds) + " s" : std::string())
                << ", periodic at a change <= " << o.periodic_tolerance << "\n";
    return progress.observer("simulate")(scene, o);
  };
  const app::Simulation sim = app::simulate(s.scene, options, observer);
  if (sim.hb) printWarnings(*sim.hb);
  progress.finish(sim.reference);
  if (s.json) std::cout << output::simulationJson(sim, s.trajectory).dump(2) << "\n";
  else output::writeSimulationText(std::cout, sim);
  reportUnsettled(sim.reference, sim.options);
  return sim.reference.periodic ? 0 : 1;
}

int runCompare(const SolveArguments& s, const TimeArguments& t) {
  app::CompareOptions options;
  options.time = timeSettings(t);
  options.from_rest = t.from_rest;
  options.hb = solveOptions(s);
  ProgressObserver progress;
  const app::Comparison c = app::compare(s.scene, options, progress.observer("reference"));
  printWarnings(c.hb);
  progress.finish(c.reference);
  reportUnsettled(c.reference, c.options);
  if (s.json) std::cout << output::comparisonJson(c).dump(2) << "\n";
  else output::writeComparisonText(std::cout, c);
  return c.succeeded() ? 0 : 1;
}

}  // namespace eqhb::cli
