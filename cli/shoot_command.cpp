#include "shoot_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "eqhb/error.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/orbits/smooth_flow.h"
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
  SolveArguments hb_args = a.hb;
  if (a.from_hb) {
    if (*a.from_hb < 1) throwInputError("--from-hb", std::to_string(*a.from_hb), "must be >= 1");
    hb_args.scene.harmonics = *a.from_hb;
  }
  orbits::ShootingOptions options;
  options.tolerance = a.tolerance;
  options.max_iterations = a.max_iterations;
  options.time_limit = a.hb.time_limit;
  options.validate();
  // --time-limit bounds the whole run: the harmonic-balance start (which
  // checks it itself), then shooting with what is left.
  const Deadline deadline(a.hb.time_limit);
  // The flow first: unsupported laws and a bad restitution fail before any solve.
  const Scene plain = loadSceneWith(hb_args.scene);
  const std::unique_ptr<orbits::Flow> flow_owner = orbits::makeFlow(plain.model, a.restitution);
  const orbits::Flow& flow = *flow_owner;

  const HbRun hb = solveHarmonicBalance(hb_args);
  const HbModel& model = hb.scene.model;
  if (hb.result.termination == Termination::kTimeLimit)
    throw TimeLimitReached("time limit of " + formatNumber(a.hb.time_limit) +
                           " s reached during the harmonic-balance start (" + hb.result.native_message + ")");
  if (!hb.result.converged())
    std::cerr << "eqhb: warning: the harmonic-balance start did not converge ("
              << terminationName(hb.result.termination) << "); shooting from its last iterate\n";
  const Eigen::VectorXd full = hb.system->fullCoefficients(hb.result.solution);
  if (deadline.limited()) options.time_limit = std::max(deadline.remaining(), 1e-3);
  ProgressLine line(verbosity().progress, hb.scene.name + " shoot");
  options.progress = shootingProgress(line, options, deadline);
  const auto orbit = orbits::shootFromHarmonicBalance(flow, model, full, options);
  line.finish(orbit.converged ? "periodic orbit" : "NOT converged");
  const double t0 = orbit.start_time;
  const int n = model.structure.dofs();

  if (a.hb.json) {
    nlohmann::json out;
    out["scene"] = hb.scene.name;
    out["omega"] = model.omega;
    out["period"] = flow.period();
    out["restitution"] = a.restitution;
    out["from_hb"] = {{"harmonics", model.basis.count()}, {"converged", hb.result.converged()},
                      {"residual_norm", hb.result.final_norm}};
    out["converged"] = orbit.converged;
    if (!orbit.converged) out["failure"] = orbit.failure;
    out["period_residual"] = orbit.period_residual;
    out["tolerance"] = options.tolerance;
    out["iterations"] = orbit.iterations;
    out["flow_evaluations"] = orbit.flow_evaluations;
    out["start_time"] = orbit.start_time;
    out["state"] = std::vector<double>(orbit.state.data(), orbit.state.data() + orbit.state.size());
    nlohmann::json dofs = nlohmann::json::array();
    for (int i = 0; i < orbit.max_abs.size(); ++i) dofs.push_back({{"dof", i + 1}, {"max_abs", orbit.max_abs[i]}});
    out["dofs"] = dofs;
    // Floquet multipliers belong to an orbit: null when none was found.
    nlohmann::json multipliers = nlohmann::json::array();
    for (int k = 0; k < orbit.multipliers.size(); ++k)
      multipliers.push_back({orbit.multipliers[k].real(), orbit.multipliers[k].imag()});
    out["multipliers"] = orbit.converged ? multipliers : nlohmann::json(nullptr);
    out["spectral_radius"] = orbit.converged ? nlohmann::json(orbit.spectral_radius) : nlohmann::json(nullptr);
    out["stable"] = orbit.converged ? nlohmann::json(orbit.stable) : nlohmann::json(nullptr);
    out["events"] = orbit.events;
    out["seconds"] = orbit.seconds;
    out["seconds_per_orbit"] = orbit.seconds_per_orbit;
    if (a.hb.trajectory && orbit.converged) {
      orbits::FlowSamples samples;
      for (int s = 0; s < model.samples; ++s) samples.times.push_back(t0 + flow.period() * s / model.samples);
      const auto run = flow.integrate(orbit.state, t0, flow.period(), false, &samples);
      if (run.ok) {
        nlohmann::json trajectory = {{"t", samples.times}};
        for (int i = 0; i < n; ++i) {
          const Eigen::VectorXd x = samples.displacement.col(i), v = samples.velocity.col(i);
          trajectory["x" + std::to_string(i + 1)] = std::vector<double>(x.data(), x.data() + x.size());
          trajectory["v" + std::to_string(i + 1)] = std::vector<double>(v.data(), v.data() + v.size());
        }
        for (int q = 0; q < samples.force.cols(); ++q) {
          const Eigen::VectorXd f = samples.force.col(q);
          trajectory["law" + std::to_string(q + 1)] = std::vector<double>(f.data(), f.data() + f.size());
        }
        out["trajectory"] = trajectory;
      }
    }
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << hb.scene.name << " at omega = " << model.omega << ", restitution " << a.restitution
              << ", from harmonic balance H = " << model.basis.count() << "\n"
              << (orbit.converged ? "periodic orbit" : "NOT converged: " + orbit.failure) << ", period residual "
              << orbit.period_residual << " after " << orbit.iterations << " Newton steps, " << orbit.seconds
              << " s (" << orbit.seconds_per_orbit << " s per orbit)\n";
    for (int i = 0; i < orbit.max_abs.size(); ++i) std::cout << "  max|x" << i + 1 << "| = " << orbit.max_abs[i] << "\n";
    if (orbit.converged) {
      std::cout << "  multipliers:";
      for (int k = 0; k < orbit.multipliers.size(); ++k)
        std::cout << " " << orbit.multipliers[k].real() << (orbit.multipliers[k].imag() >= 0 ? "+" : "")
                  << orbit.multipliers[k].imag() << "i";
      std::cout << "\n  " << (orbit.stable ? "stable" : "unstable") << " (spectral radius " << orbit.spectral_radius
                << ")\n  events per period:";
      for (const auto& [kind, count] : orbit.events) std::cout << " " << kind << " " << count;
      std::cout << "\n";
    }
  }
  if (!orbit.converged) std::cerr << "eqhb: shooting did not converge: " << orbit.failure << "\n";
  return orbit.converged ? 0 : 1;
}

}  // namespace eqhb::cli
