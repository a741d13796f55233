#include "solve_command.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/problem_scales.h"
#include "eqhb/laws/invariants.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/solvers/deadline.h"
#include "eqhb/stability/hill_stability.h"
#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
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

nlohmann::json coldStartJson(const ColdStartReport& r, const std::string& otherwise) {
  nlohmann::json out = {{"kind", r.used ? "coarse" : otherwise}};
  if (!r.used) return out;
  out["harmonics"] = r.harmonics;
  out["samples"] = r.samples;
  out["converged"] = r.coarse.converged();
  out["iterations"] = r.coarse.iterations;
  out["residual_evaluations"] = r.coarse.residual_evaluations;
  out["jacobian_evaluations"] = r.coarse.jacobian_evaluations;
  out["retried_from_zero"] = r.retried_from_zero;
  if (r.retried_from_zero) {
    out["first_attempt"] = {{"termination", terminationName(r.first_attempt.termination)},
                            {"iterations", r.first_attempt.iterations},
                            {"residual_norm", r.first_attempt.final_norm}};
  }
  return out;
}

void addStabilityFlag(CLI::App* cmd, SolveArguments& a) {
  cmd->add_flag("--stability", a.stability,
                "Stability of the solution(s): Floquet multipliers by Hill's method on the full system's weak "
                "Jacobian (stable iff all inside the unit circle)");
}

nlohmann::json stabilityJson(const HillResult& hill) {
  nlohmann::json multipliers = nlohmann::json::array(), exponents = nlohmann::json::array();
  for (const auto& e : hill.exponents) {
    multipliers.push_back({e.multiplier.real(), e.multiplier.imag()});
    exponents.push_back({e.exponent.real(), e.exponent.imag()});
  }
  nlohmann::json out = {{"stable", hill.stable},
                        {"spectral_radius", hill.spectral_radius},
                        {"multipliers", multipliers},
                        {"exponents", exponents},
                        {"state_dimension", hill.state_dimension},
                        {"pencil_size", hill.pencil_size},
                        {"eigensolver", hill.sparse ? "sparse" : "dense"},
                        {"seconds", hill.seconds}};
  if (!hill.failure.empty()) out["failure"] = hill.failure;
  return out;
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
                  "(coarse start, then zero), full (the full system), or a backend name; comma-separated, or none. "
                  "default: cold,full and Ipopt's least squares (else ceres-lm)")
      ->capture_default_str();
}

nlohmann::json fallbackJson(const FallbackReport& report) {
  nlohmann::json attempts = nlohmann::json::array();
  for (const FallbackAttempt& a : report.attempts)
    attempts.push_back({{"step", a.step},
                        {"solver", a.result.solver},
                        {"termination", terminationName(a.result.termination)},
                        {"iterations", a.result.iterations},
                        {"residual_norm", a.result.final_norm},
                        {"seconds", a.result.seconds}});
  return {{"taken", report.taken.empty() ? nlohmann::json(nullptr) : nlohmann::json(report.taken)},
          {"attempts", attempts}, {"seconds", report.seconds}};
}

nlohmann::json coefficientsJson(const HarmonicSet& basis, const Eigen::VectorXd& c) {
  nlohmann::json harmonics = nlohmann::json::array(), cos = nlohmann::json::array(),
                 sin = nlohmann::json::array();
  for (size_t h = 0; h < basis.harmonics().size(); ++h) {
    const int k = basis.harmonics()[h], o = basis.offset(static_cast<int>(h));
    harmonics.push_back(k);
    cos.push_back(c[o]);
    sin.push_back(k == 0 ? 0.0 : c[o + 1]);
  }
  return {{"harmonics", harmonics}, {"cos", cos}, {"sin", sin}};
}

nlohmann::json solutionJson(const HbModel& model, const HbSolution& solution) {
  nlohmann::json dofs = nlohmann::json::array();
  for (size_t i = 0; i < solution.displacements.size(); ++i) {
    const auto& c = solution.displacements[i];
    dofs.push_back({{"dof", i + 1}, {"max_abs", c.max_abs}, {"max_abs_velocity", c.max_abs_rate},
                    {"coefficients", coefficientsJson(model.basis, c.coefficients)}});
  }
  nlohmann::json laws = nlohmann::json::array();
  size_t q = 0;
  for (size_t l = 0; l < model.laws.size(); ++l) {
    nlohmann::json components = nlohmann::json::array();
    double max_abs = 0.0;
    for (int a = 0; a < model.laws[l].law->dimension(); ++a, ++q) {
      const auto& c = solution.forces[q];
      components.push_back({{"dof", model.laws[l].dofs[a] + 1}, {"max_abs", c.max_abs},
                            {"coefficients", coefficientsJson(model.basis, c.coefficients)}});
      max_abs = std::max(max_abs, c.max_abs);
    }
    laws.push_back({{"law", l + 1}, {"type", model.laws[l].law->type()}, {"max_abs", max_abs},
                    {"components", components}});
  }
  return {{"dofs", dofs}, {"laws", laws}};
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

HbRun solveHarmonicBalance(const SolveArguments& a) {
  HbRun run;
  run.scene = loadSceneWith(a.scene);
  const HbModel& model = run.scene.model;
  const SolverOptions options = solverOptions(a);
  // --time-limit bounds the set-up too: assembly and factorisations check it
  // between harmonics and laws, and each solve gets what the set-up left.
  const Deadline deadline(options.time_limit);
  const auto setup_start = std::chrono::steady_clock::now();
  run.system = makeHbSystem(model, !a.full, options.linear_algebra, deadline);
  run.setup_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
  HbSystem* system = run.system.get();
  // The options of one solve: the time limit less the set-up so far.
  auto withinLimit = [&](const char* before) {
    deadline.check(before);
    SolverOptions o = options;
    if (deadline.limited()) o.time_limit = deadline.remaining();
    return o;
  };

  auto solver = makeSolver(a.solver);
  const OwnedFallbackChain fallbacks(a.fallback, a.solver, "--fallback");

  Eigen::VectorXd z0 = Eigen::VectorXd::Zero(system->size());
  if (a.from_harmonics) {
    // Seed: solve at H₀, 2H₀, ... below the target H, each from the last.
    const int target = model.basis.count();
    if (*a.from_harmonics < 1 || *a.from_harmonics >= target)
      throwInputError("--from-harmonics", std::to_string(*a.from_harmonics),
                      "must be >= 1 and below --harmonics (" + std::to_string(target) + ")");
    int seed_harmonics = *a.from_harmonics;
    while (2 * seed_harmonics < target) seed_harmonics *= 2;
    HbModel seed_model = model;
    seed_model.basis = HarmonicSet(model.basis.kind(), seed_harmonics);
    Eigen::VectorXd seed;
    const SolverResult r = solveByHarmonicContinuation(seed_model, *solver, withinLimit("set-up, before the seed"),
                                                       *a.from_harmonics, !a.full, &seed);
    if (!r.converged())
      std::cerr << "eqhb: warning: the seed at H = " << seed_harmonics << " did not converge ("
                << terminationName(r.termination) << "); starting from its last iterate\n";
    z0 = system->fromFullCoefficients(transferCoefficients(seed_model, model, seed));
  }
  if (a.start_full.size()) z0 = system->fromFullCoefficients(a.start_full);
  // A cold start begins at a coarse harmonic balance, made once here.
  std::unique_ptr<CoarseStart> coarse;
  if (a.cold_start == "coarse" && !a.from_harmonics && !a.start_full.size()) {
    const auto coarse_setup = std::chrono::steady_clock::now();
    coarse = std::make_unique<CoarseStart>(model, !a.full, options.linear_algebra, deadline);
    run.setup_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - coarse_setup).count();
  }
  // Every repeat gets the same time: the limit less the set-up.
  const SolverOptions solve_options = withinLimit("set-up, before the solve");
  for (int i = 0; i < a.repeat; ++i) {
    run.result = coarse ? coarse->solve(*solver, *system, solve_options, &run.cold_start)
                        : solver->solve(*system, z0, solve_options);
    if (run.result.termination == Termination::kInvalidOptions)
      throw InputError("--option: " + run.result.native_message);
    // The time of a solve includes its coarse start.
    run.times.push_back(run.cold_start.used ? run.cold_start.seconds : run.result.seconds);
  }
  // The default path: a failed solve gets the fallback steps (once, after the repeats).
  if (!run.result.converged()) {
    const bool started_cold = !a.from_harmonics && !a.start_full.size();
    run.result = solveWithFallbacks(*system, *solver, withinLimit("the solve, before its fallbacks"), run.result,
                                    started_cold, fallbacks.chain(), &run.fallback);
    for (double& t : run.times) t += run.fallback.seconds;
  }
  std::sort(run.times.begin(), run.times.end());
  run.options = options;
  return run;
}

namespace {
// The ladder of --accuracy on the scene with every override, over the ρ
// candidates; the first H is --harmonics if given, else min(5, the scene's H).
AccuracyChoice chooseDiscretisationFor(const SolveArguments& a, const RhoCandidates& candidates) {
  const int start = a.scene.harmonics ? *a.scene.harmonics : std::min(5, candidates.models.front().basis.count());
  const SolverOptions options = solverOptions(a);
  auto solver = makeSolver(a.solver);
  return chooseDiscretisation(candidates.models, *a.accuracy.tolerance, start, a.accuracy.max_harmonics, *solver,
                              options, !a.full);
}
}  // namespace

int runSolve(const SolveArguments& given) {
  SolveArguments a = given;
  // --refine shoot: unsupported laws and a bad restitution fail before any solve.
  if (!a.refine.method.empty()) orbits::makeFlow(loadSceneWith(a.scene).model, a.refine.restitution);
  if (a.refine.method.empty() && a.refine.harmonics)
    throwInputError("--refine-harmonics", std::to_string(a.refine.harmonics), "needs --refine shoot");
  // --accuracy: choose H and N first, then report the chosen solution as usual.
  std::optional<AccuracyChoice> choice;
  RhoCandidates candidates;
  if (a.accuracy.tolerance) {
    candidates = rhoCandidates(a.scene);
    choice = chooseDiscretisationFor(a, candidates);
    const double factor = candidates.factors[choice->candidate];
    if (factor != 1.0) {
      const auto scaled = scaledRhoOverrides(candidates.scene_rho, factor);
      a.scene.overrides.insert(a.scene.overrides.end(), scaled.begin(), scaled.end());
    }
    a.scene.harmonics = choice->model.basis.count();
    a.scene.samples = choice->model.samples;
    a.from_harmonics.reset();
    a.start_full = choice->full;
  }
  const HbRun run = solveHarmonicBalance(a);
  const Scene& scene = run.scene;
  const HbModel& model = scene.model;
  const HbSystem* system = run.system.get();
  const SolverResult& result = run.result;
  const SolverOptions& options = run.options;
  const std::vector<double>& times = run.times;
  const double median = times.size() % 2 ? times[times.size() / 2]
                                         : 0.5 * (times[times.size() / 2 - 1] + times[times.size() / 2]);
  // --refine shoot: the exact orbit replaces the harmonic-balance answer.
  // With --refine-harmonics the orbit is reported on another H (`reported`).
  const Eigen::VectorXd hb_answer = system->fullCoefficients(result.solution);
  Eigen::VectorXd answer = hb_answer;
  HbModel reported = model;
  const HbSolution plain = summarize(model, answer);
  std::optional<orbits::RefinedSolution> refined;
  if (!a.refine.method.empty() && result.converged()) refined = refine(model, answer, a.refine);
  if (refined && refined->converged) {
    answer = refined->full;
    if (refined->basis.count() != model.basis.count()) reported = withHarmonics(model, refined->basis.count());
  }
  const HbSolution solution = refined && refined->converged ? refinedSummary(reported, *refined) : plain;
  // How the linear algebra went: dense or sparse, set-up, memory.
  const bool sparse_solver = useSparseAlgebra(*run.system, options);
  const auto* condensed = dynamic_cast<const CondensedSystem*>(system);
  const bool sparse_factors = condensed && condensed->factors().sparse();
  const double factor_mib = condensed ? condensed->factors().factorBytes() / 1048576.0 : 0.0;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peak_rss_mib = usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux

  // Stability of the converged solution (Hill's method, full system).
  HillResult hill;
  const bool with_stability = a.stability && result.converged();
  if (with_stability) hill = hillStability(model, hb_answer);
  std::optional<ErrorEstimate> estimate;
  if (choice && choice->estimate.refined_harmonics) estimate = choice->estimate;
  else if (a.accuracy.error_estimate && result.converged()) {
    auto solver = makeSolver(a.solver);
    estimate = estimateError(model, system->fullCoefficients(result.solution), *solver, options, !a.full);
  }
  const std::vector<LawInvariants> invariants = checkInvariants(reported, answer);
  if (a.json) {
    nlohmann::json out;
    out["scene"] = scene.name;
    out["solver"] = result.solver;
    out["system"] = system->condensed() ? "condensed" : "full";
    out["unknowns"] = system->size();
    out["omega"] = model.omega;
    out["harmonics"] = model.basis.count();
    out["highest_harmonic"] = model.basis.highest();
    out["harmonic_set"] = HarmonicSet::kindName(model.basis.kind());
    out["samples"] = model.samples;
    out["converged"] = result.converged();
    out["termination"] = terminationName(result.termination);
    out["native_code"] = result.native_code;
    out["native_message"] = result.native_message;
    out["cold_start"] = coldStartJson(run.cold_start, a.start_full.size() ? "given"
                                                      : a.from_harmonics ? "from-harmonics"
                                                                         : "zero");
    if (!run.fallback.attempts.empty()) out["fallback"] = fallbackJson(run.fallback);
    out["iterations"] = result.iterations;
    out["residual_evaluations"] = result.residual_evaluations;
    out["jacobian_evaluations"] = result.jacobian_evaluations;
    out["initial_residual_norm"] = result.initial_norm;
    out["residual_norm"] = result.final_norm;
    out["tolerance"] = options.residual_tolerance;
    out["seconds"] = median;
    out["repeats"] = a.repeat;
    out["seconds_min"] = times.front();
    out["seconds_max"] = times.back();
    out["linear_algebra"] = sparse_solver ? "sparse" : "dense";
    if (condensed) out["condensation"] = sparse_factors ? "sparse" : "dense";
    out["setup_seconds"] = run.setup_seconds;
    if (condensed) out["factor_mib"] = factor_mib;
    out["peak_rss_mib"] = peak_rss_mib;
    const nlohmann::json channels = solutionJson(reported, solution);
    out["dofs"] = channels["dofs"];
    out["laws"] = channels["laws"];
    nlohmann::json invariants_json = nlohmann::json::array();
    for (const auto& report : invariants) {
      nlohmann::json measures;
      for (const auto& [name, value] : report.violations) measures[name] = value;
      invariants_json.push_back({{"law", report.law + 1}, {"type", report.type}, {"violations", measures}});
    }
    out["invariants"] = invariants_json;
    if (with_stability) out["stability"] = stabilityJson(hill);
    if (choice) {
      out["rho"] = rhoJson(candidates.scene_rho, candidates.factors[choice->candidate]);
      out["accuracy"] = accuracyJson(*choice, *a.accuracy.tolerance, candidates.factors);
    }
    if (estimate) out["error_estimate"] = errorEstimateJson(*estimate);
    if (refined) out["refinement"] = refinementJson(*refined, plain, a.refine.restitution);
    if (a.trajectory) {
      // One period on the model's N samples: t, x per DOF, λ per law component.
      nlohmann::json t = nlohmann::json::array();
      for (int i = 0; i < reported.samples; ++i) t.push_back(2 * M_PI / model.omega * i / reported.samples);
      nlohmann::json trajectory = {{"t", t}};
      for (const auto& c : solution.displacements)
        trajectory[c.label] = std::vector<double>(c.samples.data(), c.samples.data() + c.samples.size());
      for (const auto& c : solution.forces)
        trajectory[c.label] = std::vector<double>(c.samples.data(), c.samples.data() + c.samples.size());
      out["trajectory"] = trajectory;
    }
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << scene.name << " at omega = " << model.omega << ", H = " << model.basis.count()
              << " (" << HarmonicSet::kindName(model.basis.kind()) << "), N = " << model.samples
              << ", " << (system->condensed() ? "condensed" : "full") << " system of "
              << system->size() << " unknowns\n"
              << result.summary() << "\n";
    const ColdStartReport& cold = run.cold_start;
    if (cold.used) {
      std::cout << "cold start: coarse harmonic balance at H = " << cold.harmonics << ", N = " << cold.samples << ", "
                << (cold.coarse.converged() ? "converged" : "NOT converged (started from zero)") << " in "
                << cold.coarse.iterations << " iterations, " << cold.coarse.residual_evaluations << " residual and "
                << cold.coarse.jacobian_evaluations << " Jacobian evaluations\n";
      if (cold.retried_from_zero)
        std::cout << "  the solve from it stopped (" << terminationName(cold.first_attempt.termination) << " after "
                  << cold.first_attempt.iterations << " iterations); solved again from zero (above)\n";
    }
    if (!run.fallback.attempts.empty())
      std::cout << "fallback: " << describeFallbacks(run.fallback)
                << (run.fallback.taken.empty() ? "; none converged" : "; the result above is " + run.fallback.taken + "'s")
                << "\n";
    std::cout << "linear algebra: " << (sparse_solver ? "sparse" : "dense");
    if (condensed)
      std::cout << ", A_k factored " << (sparse_factors ? "sparse (UMFPACK)" : "dense") << " ("
                << factor_mib << " MiB of factors)";
    std::cout << "; set-up " << run.setup_seconds << " s, peak RSS " << peak_rss_mib << " MiB\n";
    if (a.repeat > 1) std::cout << "median time over " << a.repeat << " solves: " << median << " s\n";
    for (const auto& c : solution.displacements)
      std::cout << "  max|" << c.label << "| = " << c.max_abs << "\n";
    for (const auto& c : solution.forces) std::cout << "  max|" << c.label << "| = " << c.max_abs << "\n";
    if (estimate)
      std::cout << "estimated relative error of max|x|: " << estimate->max_abs << " (solve at H = "
                << estimate->refined_harmonics << (estimate->available ? "" : ", which did NOT converge") << ")\n";
    if (refined)
      std::cout << "refined by shooting: " << (refined->converged ? "exact periodic orbit" : "NOT converged: " + refined->failure)
                << ", period residual " << refined->orbit.period_residual << " after " << refined->orbit.iterations
                << " Newton steps, " << refined->seconds << " s (max|x| above: the orbit's; coefficients: its truncation on H = "
                << refined->basis.count() << ")\n";
    if (choice)
      std::cout << "--accuracy " << *a.accuracy.tolerance << ": " << (choice->reached ? "reached" : "NOT reached")
                << " at H = " << model.basis.count() << ", N = " << model.samples << ", rho = "
                << rhoJson(candidates.scene_rho, candidates.factors[choice->candidate]).dump() << " in " << choice->seconds
                << " s of solves\n";
    for (const auto& report : invariants) {
      std::cout << "  law " << report.law + 1 << " (" << report.type << ") worst violations:";
      for (const auto& [name, value] : report.violations) std::cout << " " << name << " " << value;
      std::cout << "\n";
    }
    if (with_stability) {
      if (!hill.failure.empty()) {
        std::cout << "stability: not computed (" << hill.failure << ")\n";
      } else {
        std::cout << "stability: " << (hill.stable ? "stable" : "UNSTABLE") << ", spectral radius "
                  << hill.spectral_radius << " (Hill, " << hill.pencil_size << " unknowns, " << hill.seconds
                  << " s); leading multipliers:";
        for (size_t i = 0; i < hill.exponents.size() && i < 8; ++i) {
          const auto& e = hill.exponents[i];
          std::cout << " " << e.multiplier.real() << (e.multiplier.imag() < 0 ? "" : "+") << e.multiplier.imag() << "i";
        }
        std::cout << "\n";
      }
    }
  }
  if (!result.converged())
    std::cerr << "eqhb: the solve did not converge: " << terminationName(result.termination)
              << ", |g| = " << result.final_norm << " > tolerance " << options.residual_tolerance
              << (result.native_message.empty() ? "" : " (" + result.native_message + ")") << "\n";
  if (!result.converged() && !run.fallback.attempts.empty())
    std::cerr << "eqhb: fallbacks tried: " << describeFallbacks(run.fallback) << "\n";
  if (!result.converged())
    for (const std::string& advice : rhoScaleAdvice(model)) std::cerr << "eqhb: " << advice << "\n";

  if (choice && !choice->reached) {
    std::cerr << "eqhb: --accuracy " << *a.accuracy.tolerance << " not reached: " << choice->failure << "\n";
    return 1;
  }
  if (estimate && !estimate->available)
    std::cerr << "eqhb: warning: the error estimate's solve at H = " << estimate->refined_harmonics
              << " did not converge: the estimate is not reliable\n";
  if (refined && !refined->converged) {
    std::cerr << "eqhb: --refine shoot: " << refined->failure << "; reporting the harmonic-balance solution\n";
    return 1;
  }
  return result.converged() ? 0 : 1;
}

}  // namespace eqhb::cli
