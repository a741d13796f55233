#include "modes_command.h"

#include <iostream>

#include "eqhb/app/modes.h"
#include "eqhb/output/backbone_writers.h"
#include "representable_number.h"

namespace eqhb::cli {

void addModesCommand(CLI::App& app, ModesArguments& a) {
  auto* cmd = app.add_subcommand(
      "modes", "Nonlinear mode (extended periodic motion concept): frequency, damping ratio, dissipated energy and "
               "shape against modal amplitude");
  addSceneOptions(cmd, a.solve.scene);
  cmd->add_option("--mode", a.mode, "K: the mode of the structure linearised about rest, by frequency, from 1")
      ->capture_default_str();
  cmd->add_option("--from", a.from, "Smallest modal amplitude phi^T M x1 (default: 1e-2 of the scene's length scale)")
      ->check(representableNumber());
  cmd->add_option("--to", a.to, "Largest modal amplitude (default: 1e3 of the scene's length scale)")
      ->check(representableNumber());
  cmd->add_option("--points", a.points, "Amplitudes, evenly spaced in log")->capture_default_str();
  auto* json = cmd->add_flag("--json", a.solve.json, "Print one JSON object, with each point's Fourier coefficients");
  cmd->add_flag("--csv", a.csv, "Print CSV, one row a point")->excludes(json);
  cmd->add_option("--backend,--solver", a.solve.solver, "Backend name (see `eqhb solvers`)")->capture_default_str();
  cmd->add_option("--option", a.solve.backend_options, "Backend-specific option NAME=VALUE");
  cmd->add_option("--tolerance", a.solve.tolerance, "Residual tolerance on the scaled ‖g‖₂")
      ->check(representableNumber())
      ->capture_default_str();
  cmd->add_option("--max-iterations", a.solve.max_iterations, "Iteration limit per solve")->capture_default_str();
  cmd->add_option("--time-limit", a.solve.time_limit, "Seconds per solve; 0 = none")
      ->check(representableNumber())
      ->capture_default_str();
  cmd->add_option("--linear-algebra", a.solve.linear_algebra, "dense or sparse (auto: sparse for large systems)")
      ->check(CLI::IsMember({"auto", "dense", "sparse"}))
      ->capture_default_str();
}

int runModes(const ModesArguments& a) {
  app::ModesOptions options;
  options.mode = a.mode;
  options.from = a.from;
  options.to = a.to;
  options.points = a.points;
  options.solver = a.solve.solver;
  options.solver_options = solverOptions(a.solve);
  const app::ModesRun run = app::modes(a.solve.scene, options);
  if (a.solve.json) std::cout << output::backboneJson(run).dump(2) << "\n";
  else if (a.csv) output::writeBackboneCsv(std::cout, run);
  else output::writeBackboneText(std::cout, run);
  if (!run.backbone.complete())
    std::cerr << "eqhb: " << run.backbone.failed_points << " of " << run.backbone.points.size()
              << " amplitudes did not converge\n";
  return run.backbone.complete() ? 0 : 1;
}

}  // namespace eqhb::cli
