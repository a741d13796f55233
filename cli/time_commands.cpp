#include "time_commands.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <vector>
#include <nlohmann/json.hpp>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"
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

nlohmann::json referenceJson(const HbModel& model, const TimeReference& ref) {
  nlohmann::json out = {{"periodic", ref.periodic},
                        {"timed_out", ref.timed_out},
                        {"periods", ref.periods},
                        {"step", ref.step},
                        {"steps_per_period", ref.steps_per_period},
                        {"periodicity_error", ref.periodicity_error},
                        {"seconds", ref.seconds}};
  const int nb = model.basis.size();
  nlohmann::json dofs = nlohmann::json::array();
  for (int i = 0; i < model.structure.dofs(); ++i)
    dofs.push_back({{"dof", i + 1},
                    {"max_abs", ref.displacement.col(i).cwiseAbs().maxCoeff()},
                    {"max_abs_velocity", ref.velocity.col(i).cwiseAbs().maxCoeff()},
                    {"first_harmonic_amplitude",
                     firstHarmonicAmplitude(model.basis, ref.coefficients.data() + i * nb)}});
  out["dofs"] = dofs;
  nlohmann::json forces = nlohmann::json::array();
  for (int q = 0; q < ref.force.cols(); ++q)
    forces.push_back({{"component", q + 1}, {"max_abs", ref.force.col(q).cwiseAbs().maxCoeff()}});
  out["law_forces"] = forces;
  return out;
}

// The last period, sample i at t = iT/steps_per_period: "t", then per DOF
// "x<i>" and "v<i>", per law component the label of `eqhb solve`.
nlohmann::json trajectoryJson(const HbModel& model, const TimeReference& ref) {
  const int samples = static_cast<int>(ref.displacement.rows());
  std::vector<double> t(samples);
  for (int i = 0; i < samples; ++i) t[i] = 2 * M_PI / model.omega * i / ref.steps_per_period;
  auto column = [](const Eigen::MatrixXd& m, int j) {
    const Eigen::VectorXd c = m.col(j);
    return std::vector<double>(c.data(), c.data() + c.size());
  };
  nlohmann::json out = {{"t", t}};
  for (int i = 0; i < model.structure.dofs(); ++i) {
    out["x" + std::to_string(i + 1)] = column(ref.displacement, i);
    out["v" + std::to_string(i + 1)] = column(ref.velocity, i);
  }
  const HbSolution labels = summarize(model, ref.coefficients);
  for (int q = 0; q < ref.force.cols(); ++q) out[labels.forces[q].label] = column(ref.force, q);
  return out;
}

void printReference(const HbModel& model, const TimeReference& ref) {
  std::cout << "time reference: " << (ref.periodic ? "periodic" : "NOT periodic") << " after " << ref.periods
            << " periods (change " << ref.periodicity_error << "), h = " << ref.step << " ("
            << ref.steps_per_period << " steps per period), " << ref.seconds << " s\n";
  for (int i = 0; i < model.structure.dofs(); ++i)
    std::cout << "  max|x" << i + 1 << "| = " << ref.displacement.col(i).cwiseAbs().maxCoeff() << "\n";
  for (int q = 0; q < ref.force.cols(); ++q)
    std::cout << "  max|lambda" << q + 1 << "| = " << ref.force.col(q).cwiseAbs().maxCoeff() << "\n";
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

TimeOptions timeOptionsFor(const Scene& scene, const TimeArguments& t) {
  auto given = [](const CLI::Option* o) { return o && o->count() > 0; };
  TimeOptions options = t.options;
  const TimeReferenceDefaults& d = scene.time_reference;
  if (d.step && !given(t.step)) options.step = *d.step;
  if (d.theta && !given(t.theta)) options.theta = *d.theta;
  if (d.periods && !given(t.periods)) options.max_periods = *d.periods;
  if (d.periodic_tolerance && !given(t.periodic_tolerance)) options.periodic_tolerance = *d.periodic_tolerance;
  return options;
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

int runSimulate(const SolveArguments& s, const TimeArguments& t) {
  Eigen::VectorXd start;
  Scene scene = loadSceneWith(s.scene);
  if (t.from_hb) {
    const HbRun run = solveHarmonicBalance(s);
    if (!run.result.converged())
      throw std::runtime_error("--from-hb: the harmonic-balance solve did not converge (" +
                               std::string(terminationName(run.result.termination)) + ")");
    start = run.system->fullCoefficients(run.result.solution);
  }
  const TimeOptions options = timeOptionsFor(scene, t);
  options.validate();  // before the progress line shows a count of periods
  if (verbosity().verbose)
    std::cerr << "eqhb: simulate " << scene.source << ": h = " << options.step << ", theta = " << options.theta
              << ", at most " << options.max_periods << " periods"
              << (options.max_seconds > 0.0 ? " and " + formatNumber(options.max_seconds) + " s" : std::string())
              << ", periodic at a change <= " << options.periodic_tolerance << "\n";
  ProgressLine line(verbosity().progress, scene.name + " simulate");
  const TimeReference ref = integrateToSteadyState(scene.model, options, start, periodProgress(line, options));
  line.finish(ref.periodic ? "periodic" : "NOT periodic");
  if (s.json) {
    nlohmann::json out = referenceJson(scene.model, ref);
    out["scene"] = scene.name;
    out["omega"] = scene.model.omega;
    if (s.trajectory) out["trajectory"] = trajectoryJson(scene.model, ref);
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << scene.name << " at omega = " << scene.model.omega << "\n";
    printReference(scene.model, ref);
  }
  reportUnsettled(ref, options);
  return ref.periodic ? 0 : 1;
}

int runCompare(const SolveArguments& s, const TimeArguments& t) {
  const HbRun run = solveHarmonicBalance(s);
  const HbModel& model = run.scene.model;
  if (!run.result.converged())
    std::cerr << "eqhb: warning: the harmonic-balance solve did not converge ("
              << terminationName(run.result.termination) << "); errors refer to its last iterate\n";
  const Eigen::VectorXd hb = run.system->fullCoefficients(run.result.solution);
  const TimeOptions options = timeOptionsFor(run.scene, t);
  options.validate();
  ProgressLine line(verbosity().progress, run.scene.name + " reference");
  const TimeReference ref =
      integrateToSteadyState(model, options, t.from_rest ? Eigen::VectorXd() : hb, periodProgress(line, options));
  line.finish(ref.periodic ? "periodic" : "NOT periodic");
  reportUnsettled(ref, options);
  const auto errors = compareWithReference(model, hb, ref);
  if (s.json) {
    nlohmann::json out;
    out["scene"] = run.scene.name;
    out["omega"] = model.omega;
    out["harmonics"] = model.basis.count();
    out["hb"] = {{"converged", run.result.converged()},
                 {"termination", terminationName(run.result.termination)},
                 {"residual_norm", run.result.final_norm},
                 {"seconds", run.result.seconds}};
    out["reference"] = referenceJson(model, ref);
    nlohmann::json e = nlohmann::json::array();
    for (const auto& c : errors)
      e.push_back({{"channel", c.label}, {"relative_l2", c.relative_l2}, {"relative_l2_velocity", c.relative_l2_rate},
                   {"relative_max_abs", c.relative_max_abs}, {"first_harmonic_error", c.first_harmonic_error},
                   {"max_abs_hb", c.max_abs_hb}, {"max_abs_reference", c.max_abs_reference}});
    out["errors"] = e;
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << run.scene.name << " at omega = " << model.omega << ", H = " << model.basis.count() << "\n"
              << "harmonic balance: " << run.result.summary() << "\n";
    printReference(model, ref);
    std::cout << "errors (HB vs reference):\n";
    for (const auto& c : errors)
      std::cout << "  " << c.label << ": L2 " << c.relative_l2 << (c.label[0] == 'x' ? ", velocity L2 " + std::to_string(c.relative_l2_rate) : "")
                << ", max|.| " << c.max_abs_hb << " vs " << c.max_abs_reference << " (" << c.relative_max_abs
                << "), first harmonic " << c.first_harmonic_error << "\n";
  }
  return run.result.converged() && ref.periodic ? 0 : 1;
}

}  // namespace eqhb::cli
