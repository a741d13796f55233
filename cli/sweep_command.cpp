#include "sweep_command.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/backends/registry.h"

namespace eqhb::cli {

void addSweepCommand(CLI::App& app, SolveArguments& s, SweepArguments& w) {
  auto* cmd = app.add_subcommand("sweep", "Frequency-response curve by continuation in omega");
  addSceneOptions(cmd, s.scene);
  addSolverOptions(cmd, s);
  cmd->add_option("--from", w.from, "Start frequency (default: the scene's sweep.from)");
  cmd->add_option("--to", w.to, "End frequency (default: the scene's sweep.to)");
  auto* step = cmd->add_option("--step", w.step, "Grid step in omega (sequential) or initial scaled arclength step")
                   ->capture_default_str();
  cmd->add_flag("--arclength", w.arclength, "Pseudo-arclength continuation (passes turning points)");
  (void)step;
  cmd->add_option("--max-points", w.max_points, "Most points on the curve")->capture_default_str();
  cmd->add_option("--out", w.out, "Write the curve as CSV");
  cmd->add_option("--chart", w.chart, "Write a chart of the curve: PREFIX.png and PREFIX.svg (matplotlib)");
}


int runSweep(const SolveArguments& s, const SweepArguments& w) {
  const Scene scene = loadSceneWith(s.scene);
  ContinuationOptions options;
  options.from = w.from ? *w.from : scene.sweep_from.value_or(0.0);
  options.to = w.to ? *w.to : scene.sweep_to.value_or(0.0);
  if (!w.from && !scene.sweep_from) throwInputError("--from", "(missing)", "the scene has no [sweep]: give --from and --to");
  options.step = w.step;
  options.min_step = std::min(1e-6, w.step);
  options.max_step = std::max(1.0, w.step);
  options.max_points = w.max_points;
  options.condensed = !s.full;
  const SolverOptions solver_options = solverOptions(s);
  auto solver = makeSolver(s.solver);
  const int dofs = scene.model.structure.dofs();
  const bool terminal = isatty(STDERR_FILENO);
  const int expected = w.arclength ? 0 : static_cast<int>(std::abs(options.to - options.from) / options.step) + 1;
  Progress progress = [&](const CurvePoint& p, int index) {
    if (!terminal) return;
    std::fprintf(stderr, "\r  point %d%s%s  omega = %.5f  %s  max|x%d| = %-10.5g", index + 1,
                 expected ? "/" : "", expected ? std::to_string(expected).c_str() : "", p.omega,
                 p.converged ? "ok    " : "FAILED", dofs, p.converged ? p.max_abs[dofs - 1] : NAN);
    std::fflush(stderr);
  };
  const Curve curve = w.arclength ? sweepArclength(scene.model, *solver, solver_options, options, progress)
                                  : sweepSequential(scene.model, *solver, solver_options, options, progress);
  if (terminal) std::fprintf(stderr, "\n");

  const CurvePoint* peak = nullptr;
  for (const auto& p : curve.points)
    if (p.converged && (!peak || p.max_abs[dofs - 1] > peak->max_abs[dofs - 1])) peak = &p;
  std::cout << scene.name << ": " << (w.arclength ? "arclength" : "sequential") << " sweep " << options.from
            << " -> " << options.to << " with " << solver->name() << ", H = " << scene.model.basis.count() << ": "
            << curve.points.size() << " points, " << curve.failed_points << " failed, " << curve.seconds << " s\n"
            << "  stop: " << curve.stop_reason << "\n";
  if (peak)
    std::cout << "  peak: omega = " << peak->omega << ", max|x" << dofs << "| = " << peak->max_abs[dofs - 1] << "\n";
  if (!curve.fold_omegas.empty()) {
    std::cout << "  folds at omega =";
    for (double f : curve.fold_omegas) std::cout << " " << f;
    std::cout << "\n";
  } else if (w.arclength) {
    std::cout << "  no fold\n";
  }
  if (!w.out.empty()) writeCurveCsv(w.out, curve, dofs);
  if (!w.chart.empty()) {
    const std::string csv = w.out.empty() ? w.chart + ".csv" : w.out;
    if (w.out.empty()) writeCurveCsv(csv, curve, dofs);
    const std::string command = std::string("/usr/bin/python3 ") + EQHB_PLOT_CURVE + " '" + csv + "' '" + w.chart +
                                "' '" + scene.name + "'";
    if (std::system(command.c_str()) != 0)
      throw std::runtime_error("--chart: plotting failed (needs /usr/bin/python3 with matplotlib)");
  }
  return curve.failed_points == 0 && !curve.points.empty() ? 0 : 1;
}

}  // namespace eqhb::cli
