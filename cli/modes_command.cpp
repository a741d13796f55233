#include "modes_command.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "eqhb/app/modes.h"
#include "eqhb/app/synthesis.h"
#include "eqhb/output/backbone_writers.h"
#include "eqhb/output/synthesis_writers.h"
#include "hdf5_option.h"
#include "representable_number.h"
#include "terminal/progress.h"
#include "terminal/verbosity.h"

namespace eqhb::cli {

void addModesCommand(CLI::App& app, ModesArguments& a) {
  auto* cmd = app.add_subcommand(
      "modes", "Nonlinear mode (extended periodic motion concept): frequency, damping ratio, dissipated energy and "
               "shape against modal amplitude");
  addSceneOptions(cmd, a.solve.scene);
  cmd->add_option("--mode", a.modes.mode, "K: the mode of the structure linearised about rest, by frequency, from 1")
      ->capture_default_str();
  cmd->add_option("--branch", a.modes.branch,
                  "held: from the structure with sticking friction holding its DOFs, up in amplitude; sliding: from "
                  "the structure without its laws, down from --to; auto: sliding when the scene's sweep range holds "
                  "the free mode K and not the held one")
      ->check(CLI::IsMember({"auto", "held", "sliding"}))
      ->capture_default_str();
  cmd->add_option("--from", a.modes.from, "Smallest modal amplitude phi^T M x1 (default: 1e-2 of the slip onset's amplitude, else of the scene's "
                  "length scale)")
      ->check(representableNumber());
  cmd->add_option("--to", a.modes.to, "Largest modal amplitude (default: 1e3 of the slip onset's amplitude, else of the scene's length scale; "
                  "about a preload, no further than where a pressed contact would open)")
      ->check(representableNumber());
  cmd->add_option("--points", a.modes.points, "Amplitudes, evenly spaced in log")->capture_default_str();
  cmd->add_flag("--synthesis", a.modes.synthesis,
                "Also the forced response the mode predicts under the scene's forcing (single nonlinear mode "
                "synthesis), beside a forced sweep across that resonance, with their differences");
  auto* json = cmd->add_flag("--json", a.solve.json, "Print one JSON object, with each point's Fourier coefficients");
  cmd->add_flag("--csv", a.csv, "Print CSV, one row a point")->excludes(json);
  addHdf5Option(cmd, a.hdf5, "the backbone (per point amplitude, omega, damping, max|x| and coefficients)");
  cmd->add_option("--backend,--solver", a.solve.solver, "Backend name (see `eqhb solvers`)")->capture_default_str();
  auto* condensed = cmd->add_flag("--condensed", a.modes.condensed,
                                  "Solve the condensed mode system (unknowns: the law forces, omega and xi; every "
                                  "A_k factored at each new omega and xi; needs a law and a regular K)");
  cmd->add_flag("--full", "Solve the full mode system (displacements and forces; default)")->excludes(condensed);
  cmd->add_option("--option", a.solve.backend_options, "Backend-specific option NAME=VALUE");
  cmd->add_option("--tolerance", a.solve.tolerance, "Residual tolerance on the scaled ‖g‖₂")
      ->check(representableNumber())
      ->capture_default_str();
  cmd->add_option("--max-iterations", a.solve.max_iterations, "Iteration limit per solve")->capture_default_str();
  cmd->add_option("--time-limit", a.solve.time_limit, "Seconds per solve; 0 = none")
      ->check(representableNumber())
      ->capture_default_str();
  cmd->add_option("--backbone-time-limit", a.modes.backbone_time_limit,
                  "Seconds for the whole backbone; 0 = none (the amplitudes not reached are reported failed)")
      ->check(representableNumber())
      ->capture_default_str();
  cmd->add_option("--linear-algebra", a.solve.linear_algebra, "dense or sparse (auto: sparse for large systems)")
      ->check(CLI::IsMember({"auto", "dense", "sparse"}))
      ->capture_default_str();
}

int runModes(const ModesArguments& a) {
  app::ModesOptions options = a.modes;
  options.solver = a.solve.solver;
  options.solver_options = solverOptions(a.solve);
  // The progress line: amplitudes recorded (an amplitude between two folds
  // counts each time the path crosses it), the last one's ω and ζ.
  ProgressLine line(verbosity().progress, "modes");
  int recorded = 0, failed = 0;
  const auto progress = [&](const BackbonePoint& p, int index) {
    ++recorded;
    if (!p.converged) ++failed;
    char detail[128];
    std::snprintf(detail, sizeof detail, "a = %.5g  omega = %.6g  zeta = %.4g%s", p.amplitude,
                  p.converged ? p.omega : NAN, p.converged ? p.damping_ratio : NAN,
                  failed ? ("  " + std::to_string(failed) + " failed").c_str() : "");
    line.update(static_cast<double>(index + 1) / options.points,
                "amplitude " + std::to_string(index + 1) + "/" + std::to_string(options.points), detail);
  };
  const app::ModesRun run = app::modes(a.solve.scene, options, progress);
  line.finish(std::to_string(recorded) + " points, " + std::to_string(failed) + " failed");
  std::optional<app::SynthesisComparison> synthesis;
  if (a.modes.synthesis) {
    ProgressLine forced_line(verbosity().progress, "modes: forced sweep");
    forced_line.update(-1.0, "synthesis");
    synthesis = app::compareWithForcedSweep(a.solve.scene, run, options, app::SweepOptions());
    forced_line.finish();
  }
  if (a.solve.json) {
    nlohmann::json out = output::backboneJson(run);
    if (synthesis) out["synthesis"] = output::synthesisJson(*synthesis);
    std::cout << out.dump(2) << "\n";
  } else if (a.csv) {
    output::writeBackboneCsv(std::cout, run);
  } else {
    output::writeBackboneText(std::cout, run);
  }
  if (!a.hdf5.empty()) writeBackboneHdf5File(a.hdf5, run);
  // With --csv or --json, stdout is the data alone; the comparison goes to stderr.
  if (synthesis && !a.solve.json) output::writeSynthesisText(a.csv ? std::cerr : std::cout, *synthesis);
  if (!run.backbone.complete())
    std::cerr << "eqhb: " << run.backbone.failed_points << " of " << run.backbone.points.size()
              << " amplitudes did not converge\n";
  return run.backbone.complete() ? 0 : 1;
}

}  // namespace eqhb::cli
