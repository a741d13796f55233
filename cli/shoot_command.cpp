#include "shoot_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "eqhb/error.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/output/orbit_json.h"
#include "eqhb/solvers/deadline.h"
#include "representable_number.h"
#include "terminal/progress.h"
#include "terminal/verbosity.h"

namespace eqhb::cli {

void addShootCommand(CLI::App& app, ShootArguments& a) {
  auto* cmd = app.add_subcommand("shoot", "Exact periodic orbit by shooting from harmonic balance, with Floquet multipliers");
  addSceneOptions(cmd, a.hb.scene);
  cmd->add_option("--from-hb", a.from_hb, "Harmonics H of the harmonic-balance start (default: the scene's)");
  cmd->add_option("--restitution", a.restitution, "Newton impact coefficient e of contact laws, in [0, 1]")
      ->capture_default_str();
  cmd->add_option("--tolerance", a.tolerance, "Relative period residual |P(y) - y| / |y| to reach")
      ->check(representableNumber())
      ->capture_default_str();
  cmd->add_option("--max-iterations", a.max_iterations, "Newton iterations on the period map")->capture_default_str();
  cmd->add_option("--solver", a.hb.solver, "Backend of the harmonic-balance start");
  cmd->add_option("--fallback", a.hb.fallback,
                  "Steps tried when the harmonic-balance start fails (as for solve: cold, full, a backend name, "
                  "comma-separated, or none)")
      ->capture_default_str();
  cmd->add_option("--time-limit", a.hb.time_limit,
                  "Seconds for the whole run, harmonic-balance start included; 0 = none (exit 1 when reached)")
      ->check(representableNumber())
      ->capture_default_str();
  cmd->add_flag("--json", a.hb.json, "Print one JSON object");
  cmd->add_flag("--trajectory", a.hb.trajectory, "With --json: x, v and law forces at N instants of one period");
}

namespace {
// Progress of the Newton iterations on the period map: steps against the
// most allowed (or the time used against the limit, whichever is further),
// and the period residual against the tolerance.
orbits::ShootingProgress shootingProgress(ProgressLine& line, const orbits::ShootingOptions& options,
                                          const Deadline& deadline) {
  if (!line.enabled()) return orbits::ShootingProgress();
  return [&line, &deadline, options](int iterations, int evaluations, double residual) {
    double fraction = static_cast<double>(iterations) / options.max_iterations;
    if (deadline.limited()) fraction = std::max(fraction, deadline.elapsed() / deadline.seconds());
    char detail[128];
    if (std::isfinite(residual))
      std::snprintf(detail, sizeof detail, "%d period maps, residual %.3g (periodic at %.3g)", evaluations, residual,
                    options.tolerance);
    else
      std::snprintf(detail, sizeof detail, "%d period maps", evaluations);  // before the first residual
    line.update(std::min(fraction, 1.0),
                "Newton step " + std::to_string(iterations) + "/" + std::to_string(options.max_iterations), detail);
  };
}
}  // namespace

int runShoot(const ShootArguments& a) {
  app::ShootOptions options;
  options.hb = solveOptions(a.hb);
  options.from_hb = a.from_hb;
  options.restitution = a.restitution;
  options.tolerance = a.tolerance;
  options.max_iterations = a.max_iterations;
  options.trajectory = a.hb.json && a.hb.trajectory;
  // The progress line starts with shooting, after the harmonic-balance
  // start; the time limit runs from here, as the run's does.
  const Deadline deadline(a.hb.time_limit);
  std::unique_ptr<ProgressLine> line;
  const app::Orbit orbit =
      app::shoot(a.hb.scene, options, [&](const Scene& scene, const orbits::ShootingOptions& shooting) {
        line = std::make_unique<ProgressLine>(verbosity().progress, scene.name + " shoot");
        return shootingProgress(*line, shooting, deadline);
      });
  for (const std::string& w : orbit.hb.warnings) std::cerr << "eqhb: warning: " << w << "\n";
  if (line) line->finish(orbit.orbit.converged ? "periodic orbit" : "NOT converged");
  if (a.hb.json) std::cout << output::orbitJson(orbit, a.hb.trajectory).dump(2) << "\n";
  else output::writeOrbitText(std::cout, orbit);
  if (!orbit.orbit.converged) std::cerr << "eqhb: shooting did not converge: " << orbit.orbit.failure << "\n";
  return orbit.orbit.converged ? 0 : 1;
}

}  // namespace eqhb::cli
