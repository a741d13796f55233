#include "solve_command.h"

#include <iostream>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/problem_scales.h"
#include "eqhb/output/solution_text.h"
#include "flag_names.h"
#include "representable_number.h"

namespace eqhb::cli {

void addSolveCommand(CLI::App& app, SolveArguments& a) {
  auto* cmd = app.add_subcommand("solve", "Solve one scene at one frequency");
  addSceneOptions(cmd, a.scene);
  addSolverOptions(cmd, a);
  cmd->add_flag("--json", a.json, "Print one JSON object");
  cmd->add_flag("--trajectory", a.trajectory, "With --json: add the samples of x and of the law forces over one period");
  cmd->add_option("--repeat", a.repeat, "Repeat the solve and report the median time")
      ->check(CLI::Range(1, 100000));
  addAccuracyOptions(cmd, a.accuracy);
  addRefineOptions(cmd, a.refine);
  cmd->add_option("--from-harmonics", a.from_harmonics,
                  "Start from the solution at H0, 2H0, ... (continuation in H: for large H where a cold start fails)");
  cmd->add_option("--cold-start", a.cold_start,
                  "Without --from-harmonics: start from the solution of a coarse harmonic balance (about H/3 "
                  "harmonics on few samples; solved again from zero if that start fails) or from zero")
      ->check(CLI::IsMember({"coarse", "zero"}))
      ->capture_default_str();
  addStabilityFlag(cmd, a);
}

void addStabilityFlag(CLI::App* cmd, SolveArguments& a) {
  cmd->add_flag("--stability", a.stability,
                "Stability of the solution(s): Floquet multipliers (stable iff all inside the unit circle) by "
                "--stability-method");
  cmd->add_option("--stability-method", a.stability_method,
                  "hill: Hill's method (any law, the reference); monodromy: the monodromy of the linearised "
                  "dynamics over the solution with saltation at the switching instants (grounded Coulomb 1D "
                  "minmax/projection and Signorini laws; converges to the exact multipliers as H grows; above 20 "
                  "DOFs on the law DOFs and the modes that are slow or weakly damped: 19 us a point on "
                  "friction-1d, 0.15 ms on beam-damper against Hill's 24 ms); shooting: the exact Floquet "
                  "multipliers of the periodic orbit shot from the solution on the exact event-driven flow "
                  "(grounded laws with an exact flow; independent of H; a point where shooting fails or reaches "
                  "another orbit is answered by the monodromy, else Hill, and says so); auto: the monodromy where "
                  "it applies, else Hill")
      ->check(CLI::IsMember({"hill", "monodromy", "shooting", "auto"}))
      ->capture_default_str();
  cmd->add_option("--stability-time-limit", a.stability_time_limit,
                  "Seconds for the stability of a whole curve (sweep), checked after each point; the points not "
                  "reached get no verdict and the output says how many were analysed (0: none)")
      ->capture_default_str();
}

void addSolverOptions(CLI::App* cmd, SolveArguments& a) {
  cmd->add_option("--solver", a.solver, "Backend name (see `eqhb solvers`)");
  auto* condensed = cmd->add_flag("--condensed", "Solve the condensed system (unknowns: law forces; default)");
  cmd->add_flag("--full", a.full, "Solve the full system (displacements and forces)")->excludes(condensed);
  cmd->add_option("--option", a.backend_options, "Backend-specific option NAME=VALUE");
  cmd->add_option("--tolerance", a.tolerance, "Residual tolerance on ‖g‖₂")
      ->check(representableNumber())
      ->capture_default_str();
  cmd->add_option("--max-iterations", a.max_iterations, "Iteration limit")->capture_default_str();
  cmd->add_option("--max-evaluations", a.max_evaluations, "Residual evaluation limit")->capture_default_str();
  cmd->add_option("--time-limit", a.time_limit,
                  "Seconds per solve, set-up (assembly, factorisations) included; 0 = none")
      ->check(representableNumber())
      ->capture_default_str();
  cmd->add_option("--linear-algebra", a.linear_algebra,
                  "dense or sparse Jacobians and factorisations (auto: sparse for large systems)")
      ->check(CLI::IsMember({"auto", "dense", "sparse"}))
      ->capture_default_str();
  cmd->add_option("--fallback", a.fallback,
                  "Steps tried, in order, when a solve (a sweep's point after its halved steps) fails: cold "
                  "(coarse start, then zero), full (the full system), condensed (the condensed system, then the full "
                  "one from its answer), forcing (the dynamic loads raised from a quarter to the whole, each solve from the "
                  "last), omega (continuation in omega from omega/2 up, else from 2 omega down), a backend name, or full:NAME "
                  "(that backend on the full system); comma-separated, or none. "
                  "default: cold,full,condensed, Ipopt's least squares (else ceres-lm), full:ceres-lm, forcing, omega")
      ->capture_default_str();
}

SolverOptions solverOptions(const SolveArguments& a) {
  SolverOptions options;
  options.residual_tolerance = a.tolerance;
  options.max_iterations = a.max_iterations;
  options.max_evaluations = a.max_evaluations;
  options.time_limit = a.time_limit;
  if (a.linear_algebra == "dense") options.linear_algebra = LinearAlgebra::kDense;
  else if (a.linear_algebra == "sparse") options.linear_algebra = LinearAlgebra::kSparse;
  else if (a.linear_algebra == "auto") options.linear_algebra = LinearAlgebra::kAuto;
  else throwInputError("--linear-algebra", a.linear_algebra, "must be auto, dense or sparse");
  for (const auto& kv : a.backend_options) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) throwInputError("--option", kv, "must be NAME=VALUE");
    options.backend[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  std::string why;
  if (!options.isValid(&why)) throw InputError(why);
  return options;
}

void readSolverChoice(const SolveArguments& a, app::SolverChoice* o) {
  o->solver = a.solver;
  o->condensed = !a.full;
  o->solver_options = solverOptions(a);
  o->fallback = a.fallback;
}

void readSolutionChecks(const SolveArguments& a, app::SolutionChecks* o) {
  o->stability = a.stability;
  o->stability_method = a.stability_method;
  o->stability_time_limit = a.stability_time_limit;
  o->error_estimate = a.accuracy.error_estimate;
  o->accuracy = a.accuracy.tolerance;
  o->max_harmonics = a.accuracy.max_harmonics;
  o->accuracy_test = a.accuracy.test;
}

app::SolveOptions solveOptions(const SolveArguments& a) {
  app::SolveOptions o;
  readSolverChoice(a, &o);
  readSolutionChecks(a, &o);
  o.cold_start = a.cold_start;
  o.from_harmonics = a.from_harmonics;
  o.repeat = a.repeat;
  o.refine = a.refine.method;
  o.restitution = a.refine.restitution;
  o.refine_harmonics = a.refine.harmonics;
  return o;
}

namespace {
// Why the exit code is not 0, on stderr.
void reportFailures(const app::Solution& s) {
  const SolverResult& result = s.run.result;
  if (!result.converged())
    std::cerr << "eqhb: the solve did not converge: " << terminationName(result.termination)
              << ", |g| = " << result.final_norm << " > tolerance " << s.run.options.residual_tolerance
              << (result.native_message.empty() ? "" : " (" + result.native_message + ")") << "\n";
  if (!result.converged() && !s.run.fallback.attempts.empty())
    std::cerr << "eqhb: fallbacks tried: " << describeFallbacks(s.run.fallback) << "\n";
  if (!result.converged())
    for (const std::string& advice : scaleAdvice(s.model())) std::cerr << "eqhb: " << advice << "\n";
  if (s.accuracy && !s.accuracy->choice.reached) {
    std::cerr << "eqhb: --accuracy " << s.accuracy->tolerance
              << " not reached: " << withFlagNames(s.accuracy->choice.failure) << "\n";
    return;
  }
  if (s.error_estimate && !s.error_estimate->available)
    std::cerr << "eqhb: warning: the error estimate's solve at H = " << s.error_estimate->refined_harmonics
              << " did not converge: the estimate is not reliable\n";
  if (s.refinement && !s.refinement->converged)
    std::cerr << "eqhb: --refine shoot: " << s.refinement->failure << "; reporting the harmonic-balance solution\n";
}
}  // namespace

app::HbRun solveHarmonicBalance(const SolveArguments& a) {
  app::HbRun run = app::solveHarmonicBalance(a.scene, solveOptions(a));
  for (const std::string& w : run.warnings) std::cerr << "eqhb: warning: " << w << "\n";
  return run;
}

int runSolve(const SolveArguments& a) {
  const app::Solution s = app::solve(a.scene, solveOptions(a));
  for (const std::string& w : s.run.warnings) std::cerr << "eqhb: warning: " << w << "\n";
  if (a.json) std::cout << output::solutionJson(s, a.trajectory).dump(2) << "\n";
  else output::writeSolutionText(std::cout, s);
  reportFailures(s);
  return s.succeeded() ? 0 : 1;
}

}  // namespace eqhb::cli
