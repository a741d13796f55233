#include "eqhb/app/solve.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/preload/operating_point.h"
#include "eqhb/solvers/deadline.h"
#include "eqhb/stability/curve_stability.h"
#include "eqhb/stability/multiplier_stability.h"

namespace eqhb::app {

double HbRun::medianSeconds() const {
  if (times.empty()) return 0.0;
  const size_t n = times.size();
  return n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
}

bool Solution::succeeded() const {
  if (accuracy && !accuracy->choice.reached) return false;
  if (refinement && !refinement->converged) return false;
  return converged();
}

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The start of a continuation in H: the solutions at H₀, 2H₀, ... below the
// model's H, each from the last, carried over to the model's basis.
Eigen::VectorXd seedByHarmonics(const HbModel& model, int from_harmonics, const SolveOptions& o, Solver& solver,
                                const SolverOptions& options, HbRun* run) {
  const int target = model.basis.count();
  if (from_harmonics >= target)
    throwInputError("from_harmonics", std::to_string(from_harmonics),
                    "must be >= 1 and below harmonics (" + std::to_string(target) + ")");
  int seed_harmonics = from_harmonics;
  while (2 * seed_harmonics < target) seed_harmonics *= 2;
  HbModel seed_model = model;
  seed_model.basis = HarmonicSet(model.basis.kind(), seed_harmonics);
  Eigen::VectorXd seed;
  const SolverResult r = solveByHarmonicContinuation(seed_model, solver, options, from_harmonics, o.condensed, &seed);
  if (!r.converged())
    run->warnings.push_back("the seed at H = " + std::to_string(seed_harmonics) + " did not converge (" +
                            terminationName(r.termination) + "); starting from its last iterate");
  return transferCoefficients(seed_model, model, seed);
}

void checkInitial(const HbModel& model, const Eigen::VectorXd& initial) {
  const Eigen::Index full_size =
      static_cast<Eigen::Index>(model.basis.size()) * (model.structure.dofs() + model.lawComponents());
  if (initial.size() != full_size)
    throwInputError("initial", "(" + std::to_string(initial.size()) + " values)",
                    "must be a full coefficient vector [x; lambda] of " + std::to_string(full_size) +
                        " values (the \"full\" entry of a solution)");
}

}  // namespace

HbRun solveHarmonicBalance(const SceneSettings& scene, const SolveOptions& o) {
  validate(o);
  HbRun run;
  run.scene = loadScene(scene);
  const HbModel& model = run.scene.model;
  const SolverOptions& options = o.solver_options;
  // time_limit bounds the set-up too: assembly and factorisations check it
  // between harmonics and laws, and each solve gets what the set-up left.
  const Deadline deadline(options.time_limit);
  const auto setup_start = std::chrono::steady_clock::now();
  run.system = makeHbSystem(model, o.condensed, options.linear_algebra, deadline);
  run.setup_seconds = secondsSince(setup_start);
  HbSystem& system = *run.system;
  // The options of one solve: the time limit less the set-up so far.
  auto withinLimit = [&](const char* before) {
    deadline.check(before);
    SolverOptions limited = options;
    if (deadline.limited()) limited.time_limit = deadline.remaining();
    return limited;
  };

  auto solver = makeSolver(o.solver);
  const OwnedFallbackChain owned_fallbacks(o.fallback, o.solver, "fallback");
  FallbackChain fallbacks = owned_fallbacks.chain();
  if (run.scene.at_rest) fallbacks.at_rest = std::make_shared<const StaticContactState>(*run.scene.at_rest);

  Eigen::VectorXd z0 = Eigen::VectorXd::Zero(system.size());
  run.start = "zero";
  // Under a preload the start is the response linearised about the static
  // state (operating_point.h).
  if (run.scene.at_rest && !o.from_harmonics && !o.initial.size()) {
    z0 = system.fromFullCoefficients(
        linearisedStart(model, *run.scene.at_rest, withinLimit("set-up, before the start")));
    run.start = "preload";
  }
  if (o.from_harmonics) {
    z0 = system.fromFullCoefficients(
        seedByHarmonics(model, *o.from_harmonics, o, *solver, withinLimit("set-up, before the seed"), &run));
    run.start = "from-harmonics";
  }
  if (o.initial.size()) {
    checkInitial(model, o.initial);
    z0 = system.fromFullCoefficients(o.initial);
    run.start = "given";
  }
  // A cold start begins at a coarse harmonic balance, made once here.
  const bool started_cold = !o.from_harmonics && !o.initial.size() && !run.scene.at_rest;
  std::unique_ptr<CoarseStart> coarse;
  if (o.cold_start == "coarse" && started_cold) {
    const auto coarse_setup = std::chrono::steady_clock::now();
    coarse = std::make_unique<CoarseStart>(model, o.condensed, options.linear_algebra, deadline);
    run.setup_seconds += secondsSince(coarse_setup);
  }
  // Every repeat gets the same time: the limit less the set-up.
  const SolverOptions solve_options = withinLimit("set-up, before the solve");
  for (int i = 0; i < o.repeat; ++i) {
    run.result = coarse ? coarse->solve(*solver, system, solve_options, &run.cold_start)
                        : solver->solve(system, z0, solve_options);
    if (run.result.termination == Termination::kInvalidOptions)
      throw InputError("options: " + run.result.native_message);
    // The time of a solve includes its coarse start.
    run.times.push_back(run.cold_start.used ? run.cold_start.seconds : run.result.seconds);
  }
  if (run.cold_start.used) run.start = "coarse";
  // The default path: a failed solve gets the fallback steps (once, after the repeats).
  if (!run.result.converged()) {
    run.result = solveWithFallbacks(system, *solver, withinLimit("the solve, before its fallbacks"), run.result,
                                    started_cold, fallbacks, &run.fallback);
    for (double& t : run.times) t += run.fallback.seconds;
  }
  std::sort(run.times.begin(), run.times.end());
  run.options = options;
  return run;
}

namespace {

// The accuracy ladder on the scene over the ρ candidates; the first H is the
// scene settings' harmonics if given, else min(5, the scene's H).
AccuracyReport chooseDiscretisationFor(const SceneSettings& scene, const SolveOptions& o) {
  AccuracyReport report;
  report.tolerance = *o.accuracy;
  report.candidates = rhoCandidates(scene);
  const int start = scene.harmonics ? *scene.harmonics : std::min(5, report.candidates.models.front().basis.count());
  auto solver = makeSolver(o.solver);
  const OwnedFallbackChain fallbacks(o.fallback, o.solver, "fallback");
  report.choice = chooseDiscretisation(report.candidates.models, *o.accuracy, start, o.max_harmonics, *solver,
                                       o.solver_options, o.condensed,
                                       AccuracyTestOptions{parseAccuracyTestChoice(o.accuracy_test)},
                                       fallbacks.chain());
  return report;
}

LinearAlgebraReport linearAlgebraOf(const HbRun& run) {
  LinearAlgebraReport out;
  out.sparse_solver = useSparseAlgebra(*run.system, run.options);
  const auto* condensed = dynamic_cast<const CondensedSystem*>(run.system.get());
  out.condensation = condensed != nullptr;
  out.sparse_factors = condensed && condensed->factors().sparse();
  out.factor_mib = condensed ? condensed->factors().factorBytes() / 1048576.0 : 0.0;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  out.peak_rss_mib = usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
  return out;
}

// The refinement's answer as the one reported: the truncation's
// coefficients, the exact orbit's max|x| per DOF.
HbSolution refinedSummary(const HbModel& model, const orbits::RefinedSolution& refined) {
  HbSolution out = summarize(model, refined.full);
  for (size_t i = 0; i < out.displacements.size(); ++i) out.displacements[i].max_abs = refined.max_abs[i];
  return out;
}

}  // namespace

Solution solve(const SceneSettings& given_scene, const SolveOptions& given) {
  validate(given);
  SceneSettings scene = given_scene;
  SolveOptions o = given;
  // refine: unsupported laws and a bad restitution fail before any solve.
  if (!o.refine.empty()) orbits::makeFlow(loadScene(scene).model, o.restitution);
  // accuracy: choose H, N and ρ first, then solve from the chosen solution.
  std::optional<AccuracyReport> accuracy;
  if (o.accuracy) {
    accuracy = chooseDiscretisationFor(scene, o);
    const double factor = accuracy->rhoFactor();
    if (factor != 1.0) {
      const auto scaled = scaledRhoOverrides(accuracy->candidates.scene_rho, factor);
      scene.overrides.insert(scene.overrides.end(), scaled.begin(), scaled.end());
    }
    scene.harmonics = accuracy->choice.model.basis.count();
    scene.samples = accuracy->choice.model.samples;
    o.from_harmonics.reset();
    o.initial = accuracy->choice.full;
  }
  Solution s;
  s.run = solveHarmonicBalance(scene, o);
  s.accuracy = std::move(accuracy);
  s.restitution = o.restitution;
  const HbModel& model = s.run.scene.model;
  const Eigen::VectorXd hb_answer = s.run.full();
  s.reported = model;
  s.full = hb_answer;
  s.plain = summarize(model, hb_answer);
  // refine: the exact orbit replaces the harmonic-balance answer, on
  // refine_harmonics if given.
  if (!o.refine.empty() && s.converged()) {
    orbits::RefinementOptions refinement;
    refinement.restitution = o.restitution;
    refinement.output_harmonics = o.refine_harmonics;
    s.refinement = orbits::refineByShooting(model, hb_answer, refinement);
  }
  const bool refined = s.refinement && s.refinement->converged;
  if (refined) {
    s.full = s.refinement->full;
    if (s.refinement->basis.count() != model.basis.count())
      s.reported = withHarmonics(model, s.refinement->basis.count());
  }
  s.summary = refined ? refinedSummary(s.reported, *s.refinement) : s.plain;
  s.linear_algebra = linearAlgebraOf(s.run);
  // The stability of the orbit reported: a refined answer's is the exact
  // orbit's own (its multipliers from shooting), not the harmonic balance's
  // it started from, which may be another orbit (another impact law).
  if (o.stability && s.converged() && refined) {
    s.stability = stabilityFromMultipliers(s.refinement->orbit.multipliers, 2.0 * M_PI / model.omega, 0.0, "shooting");
  } else if (o.stability && s.converged()) {
    HillOptions stability;
    stability.method = o.stability_method;
    s.stability = analyseStability(model, hb_answer, stability);
  }
  if (s.accuracy && s.accuracy->choice.estimate.refined_harmonics) {
    s.error_estimate = s.accuracy->choice.estimate;
  } else if (o.error_estimate && s.converged()) {
    auto solver = makeSolver(o.solver);
    s.error_estimate = estimateError(model, hb_answer, *solver, s.run.options, o.condensed);
  }
  s.invariants = checkInvariants(s.reported, s.full);
  return s;
}

}  // namespace eqhb::app
