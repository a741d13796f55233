#include "eqhb/continuation/fallback_chain.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/scenes/scene.h"
#include "check_support.h"

namespace eqhb {
namespace {

using test::scaledResidualNorm;

// A solve of `system` from rest (zero unknowns).
SolverResult solveFromRest(HbSystem& system, Solver& solver, const SolverOptions& options) {
  return solver.solve(system, Eigen::VectorXd::Zero(system.size()), options);
}

// A shipped problem with `overrides`, its system (condensed or full) and the
// own dogleg's solve of it from rest.
struct SolvedFromRest {
  SolvedFromRest(const std::string& problem, const std::vector<std::string>& overrides, bool condensed)
      : scene(loadScene(test::problem(problem), overrides)),
        system(makeHbSystem(scene.model, condensed)),
        solver(makeSolver("dogleg")),
        result(solveFromRest(*system, *solver, options)) {}
  const Scene scene;
  const std::unique_ptr<HbSystem> system;
  const std::unique_ptr<Solver> solver;
  const SolverOptions options;
  const SolverResult result;
};

// friction-2d with the tanh friction form on the full system: the own dogleg
// stalls from rest (not_progressing, |g| 0.019), and so do its coarse start and
// Ipopt's least squares, while the condensed system converges cold. The
// chain's "condensed" step solves it there and polishes the answer on the
// full system, so the result is a converged solve of the full system itself.
TEST(FallbackChain, AFullSystemThatStallsIsSolvedOnTheCondensedSystem) {
  const SolvedFromRest s("friction-2d.toml", {"law[0].form=\"tanh\""}, false);
  HbSystem& full = *s.system;
  ASSERT_FALSE(s.result.converged());

  const FallbackChain without = FallbackChain::parse("cold,full", "fallback", [](const std::string&) { return nullptr; });
  EXPECT_FALSE(solveWithFallbacks(full, *s.solver, s.options, s.result, false, without, nullptr).converged());

  const FallbackChain chain = FallbackChain::standard(nullptr);
  FallbackReport report;
  const SolverResult r = solveWithFallbacks(full, *s.solver, s.options, s.result, true, chain, &report);
  ASSERT_TRUE(r.converged()) << describeFallbacks(report);
  EXPECT_EQ(report.taken, "condensed");
  // The answer is the full system's: its residual, in its own scales, within tolerance there.
  EXPECT_LE(scaledResidualNorm(full, r.solution), s.options.residual_tolerance);
  // And it is the condensed system's solution.
  auto condensed = makeHbSystem(s.scene.model, true);
  const SolverResult direct = solveFromRest(*condensed, *s.solver, s.options);
  ASSERT_TRUE(direct.converged());
  EXPECT_LT((full.fullCoefficients(r.solution) - condensed->fullCoefficients(direct.solution)).norm(),
            1e-6 * condensed->fullCoefficients(direct.solution).norm());
}

// Backend-specific options (`--option`) belong to the failed solve's backend:
// the chain's other backend runs on its own defaults instead of refusing
// them. friction-2d (tanh form) on the full system, which the own dogleg and
// its coarse start stall on, with a dogleg option set: Ipopt's least squares
// still gets its turn (it refused the option, invalid_options, before).
TEST(FallbackChain, AnotherBackendRunsOnItsOwnDefaults) {
  if (!test::registered("ipopt-ls")) GTEST_SKIP() << "built without the Ipopt backend";
  const Scene scene = loadScene(test::problem("friction-2d.toml"), {"law[0].form=\"tanh\""});
  auto full = makeHbSystem(scene.model, false);
  auto solver = makeSolver("dogleg");
  auto backup = makeSolver("ipopt-ls");
  SolverOptions options;
  options.backend["factorisation"] = "qr";
  const SolverResult failed = solveFromRest(*full, *solver, options);
  ASSERT_FALSE(failed.converged());
  FallbackChain chain;
  chain.steps = {"ipopt-ls"};
  chain.solvers = {backup.get()};
  FallbackReport report;
  solveWithFallbacks(*full, *solver, options, failed, true, chain, &report);
  ASSERT_EQ(report.attempts.size(), 1u);
  EXPECT_NE(report.attempts[0].result.termination, Termination::kInvalidOptions) << describeFallbacks(report);
  EXPECT_GT(report.attempts[0].result.iterations, 0) << describeFallbacks(report);
}

// On the condensed system the step has nothing to add and is skipped.
TEST(FallbackChain, TheCondensedStepIsSkippedOnTheCondensedSystem) {
  const SolvedFromRest s("contact.toml", {"law[0].form=\"sign-square\""}, true);
  ASSERT_FALSE(s.result.converged());
  FallbackReport report;
  const FallbackChain chain =
      FallbackChain::parse("condensed", "fallback", [](const std::string&) { return nullptr; });
  solveWithFallbacks(*s.system, *s.solver, s.options, s.result, true, chain, &report);
  EXPECT_TRUE(report.attempts.empty());
}

// contact at ω = 0.5 on H = 40: the own dogleg stalls from rest, from the
// coarse start and on the full system at a local minimum of ‖g‖ (0.013), and
// so does Ipopt's least squares; continuation in H from 1, 5 or 10 stalls
// too. The forcing homotopy (a quarter of the load, then half, then all)
// converges, and its answer is a solve of the condensed system itself.
TEST(FallbackChain, AContactThatStallsEverywhereIsSolvedByTheForcingHomotopy) {
  const Scene scene = loadScene(test::problem("contact.toml"), {"harmonic_balance.harmonics=40"});
  auto condensed = makeHbSystem(scene.model, true);
  condensed->setOmega(0.5);
  auto solver = makeSolver("dogleg");
  const SolverOptions options;
  const SolverResult failed = solveFromRest(*condensed, *solver, options);
  ASSERT_FALSE(failed.converged());
  const FallbackChain without =
      FallbackChain::parse("cold,full,condensed", "fallback", [](const std::string&) { return nullptr; });
  EXPECT_FALSE(solveWithFallbacks(*condensed, *solver, options, failed, false, without, nullptr).converged());

  FallbackReport report;
  const SolverResult r =
      solveWithFallbacks(*condensed, *solver, options, failed, true, FallbackChain::standard(nullptr), &report);
  ASSERT_TRUE(r.converged()) << describeFallbacks(report);
  EXPECT_EQ(report.taken, "forcing");
  EXPECT_LE(scaledResidualNorm(*condensed, r.solution), options.residual_tolerance);
  // The wall is touched: the answer is not the linear response of the scaled-down load.
  EXPECT_GT(condensed->fullCoefficients(r.solution).tail(scene.model.basis.size()).norm(), 0.1);
}

// The damper above its peak (omega = 1.3, H = 15): the own dogleg stalls on
// the condensed system from its cold start (|g| 0.049) and on the full one
// (0.063), and so do Ipopt's least squares and the forcing homotopy; Ceres'
// Levenberg-Marquardt stalls on the condensed system too (|g| 0.32 after 200
// iterations) but converges on the full one in about 12. The step
// "full:ceres-lm" is that backend on the full system, its answer the
// condensed system's unknowns; the step "ceres-lm" before it, the same
// backend on the condensed system, fails.
TEST(FallbackChain, ADamperThatStallsOnTheCondensedSystemIsSolvedByAnotherBackendOnTheFullOne) {
  if (!test::registered("ceres-lm")) GTEST_SKIP() << "built without the Ceres backend";
  const Scene scene = loadScene(test::problem("damper.toml"), {"harmonic_balance.harmonics=15"});
  auto condensed = makeHbSystem(scene.model, true);
  condensed->setOmega(1.3);
  auto solver = makeSolver("dogleg");
  auto lm = makeSolver("ceres-lm");
  SolverOptions options;
  options.max_iterations = 200;  // LM on the condensed system would spend its 1000 and still stall
  const SolverResult failed = solveFromRest(*condensed, *solver, options);
  ASSERT_FALSE(failed.converged());

  auto lm_by_name = [&](const std::string& name) -> Solver* { return name == "ceres-lm" ? lm.get() : nullptr; };
  const FallbackChain chain = FallbackChain::parse("cold,full,ceres-lm,full:ceres-lm", "fallback", lm_by_name);
  ASSERT_EQ(chain.solvers.back(), lm.get());
  FallbackReport report;
  const SolverResult r = solveWithFallbacks(*condensed, *solver, options, failed, false, chain, &report);
  ASSERT_TRUE(r.converged()) << describeFallbacks(report);
  EXPECT_EQ(report.taken, "full:ceres-lm");
  ASSERT_EQ(report.attempts.size(), 4u) << describeFallbacks(report);
  for (size_t i = 0; i < 3; ++i) EXPECT_FALSE(report.attempts[i].result.converged()) << describeFallbacks(report);
  EXPECT_EQ(report.attempts[3].result.solver, "ceres-lm");
  // The answer, in the condensed unknowns, solves the full system: its
  // residual there, in the full system's scales, within tolerance.
  auto full = makeHbSystem(scene.model, false);
  full->setOmega(1.3);
  EXPECT_LE(scaledResidualNorm(*full, full->fromFullCoefficients(condensed->fullCoefficients(r.solution))),
            options.residual_tolerance);
}

// full:NAME names a backend as NAME does: an unknown one is refused, naming the field.
TEST(FallbackChain, RefusesAFullStepWithAnUnknownBackend) {
  auto none = [](const std::string&) -> Solver* { return nullptr; };
  for (const char* text : {"cold,full:nonsense", "full:", "full:full"})
    try {
      FallbackChain::parse(text, "fallback", none);
      ADD_FAILURE() << text << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("fallback"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("unknown step full:"), std::string::npos) << e.what();
    }
}

// The default path: Ceres' LM on the full system after the backup backend,
// before the forcing homotopy; none when LM is the solve's own backend.
TEST(FallbackChain, TheDefaultTriesLevenbergMarquardtOnTheFullSystemBeforeTheForcing) {
  if (!test::registered("ceres-lm")) GTEST_SKIP() << "built without the Ceres backend";
  const OwnedFallbackChain with_dogleg("default", "dogleg", "fallback");
  const std::vector<std::string>& steps = with_dogleg.chain().steps;
  ASSERT_GE(steps.size(), 2u);
  ASSERT_GE(steps.size(), 3u);
  EXPECT_EQ(steps[steps.size() - 3], "full:ceres-lm");
  EXPECT_EQ(steps[steps.size() - 2], "forcing");
  EXPECT_EQ(steps.back(), "omega");
  EXPECT_EQ(with_dogleg.chain().solvers[steps.size() - 3]->name(), "ceres-lm");
  const OwnedFallbackChain with_lm("default", "ceres-lm", "fallback");
  const std::vector<std::string>& own = with_lm.chain().steps;
  EXPECT_EQ(std::find(own.begin(), own.end(), "full:ceres-lm"), own.end());
  EXPECT_THROW(OwnedFallbackChain("cold,full:nonsense", "dogleg", "fallback"), InputError);
}

TEST(FallbackChain, ParsesTheForcingAndOmegaStepsAndPutsThemLast) {
  auto none = [](const std::string&) -> Solver* { return nullptr; };
  EXPECT_EQ(FallbackChain::parse("forcing,cold", "fallback", none).steps,
            (std::vector<std::string>{"forcing", "cold"}));
  EXPECT_THROW(FallbackChain::parse("forcing,forcing", "fallback", none), InputError);
  EXPECT_EQ(FallbackChain::parse("omega,cold", "fallback", none).steps,
            (std::vector<std::string>{"omega", "cold"}));
  EXPECT_THROW(FallbackChain::parse("omega,omega", "fallback", none), InputError);
  const std::vector<std::string>& standard = FallbackChain::standard(nullptr).steps;
  ASSERT_GE(standard.size(), 2u);
  EXPECT_EQ(standard[standard.size() - 2], "forcing");
  EXPECT_EQ(standard.back(), "omega");
  // An arclength bridge goes without continuation in omega, and only without it.
  EXPECT_EQ(FallbackChain::standard(nullptr).withoutOmegaContinuation().steps,
            (std::vector<std::string>{"cold", "full", "condensed", "forcing"}));
  // A sweep's warm points go without it, and without a backend on the full system.
  const FallbackChain warm = FallbackChain::standard(nullptr).forWarmPoints();
  EXPECT_EQ(warm.steps, (std::vector<std::string>{"cold", "full", "condensed"}));
  EXPECT_EQ(warm.solvers.size(), warm.steps.size());
  const std::unique_ptr<Solver> backend = makeSolver("dogleg");
  const FallbackChain backends =
      FallbackChain::parse("full,dogleg,full:dogleg,forcing", "fallback", [&](const std::string&) {
        return backend.get();
      }).forWarmPoints();
  EXPECT_EQ(backends.steps, (std::vector<std::string>{"full", "dogleg"}));
  EXPECT_EQ(backends.solvers, (std::vector<Solver*>{nullptr, backend.get()}));
}

TEST(FallbackChain, ParsesTheCondensedStepAndRefusesItTwice) {
  auto none = [](const std::string&) -> Solver* { return nullptr; };
  EXPECT_EQ(FallbackChain::parse("cold,condensed", "fallback", none).steps,
            (std::vector<std::string>{"cold", "condensed"}));
  EXPECT_THROW(FallbackChain::parse("condensed,condensed", "fallback", none), InputError);
  EXPECT_EQ(FallbackChain::standard(nullptr).steps,
            (std::vector<std::string>{"cold", "full", "condensed", "forcing", "omega"}));
}

// penalty-contact at ω = 0.7, below its hardening peak (0.79): the own
// dogleg stalls from rest, and so do the cold start, the full system and the
// forcing homotopy (|g| 0.45), while the sequential sweep from 0.3 passes 0.7
// converged. The chain's "omega" step, continuation in ω from a frequency
// where the cold start converges, solves it, and its answer is the sweep's
// point at 0.7.
TEST(FallbackChain, APenaltyContactBelowItsPeakIsSolvedByContinuationInOmega) {
  const Scene scene = loadScene(test::problem("penalty-contact.toml"));
  HbModel at = scene.model;
  at.omega = 0.7;
  auto condensed = makeHbSystem(at, true);
  auto solver = makeSolver("dogleg");
  const SolverOptions options;
  const SolverResult failed = solveFromRest(*condensed, *solver, options);
  ASSERT_FALSE(failed.converged());
  auto none = [](const std::string&) -> Solver* { return nullptr; };
  const FallbackChain without = FallbackChain::parse("cold,full,condensed,forcing", "fallback", none);
  EXPECT_FALSE(solveWithFallbacks(*condensed, *solver, options, failed, true, without, nullptr).converged());

  FallbackReport report;
  const SolverResult r =
      solveWithFallbacks(*condensed, *solver, options, failed, true, FallbackChain::standard(nullptr), &report);
  ASSERT_TRUE(r.converged()) << describeFallbacks(report);
  EXPECT_EQ(report.taken, "omega");
  EXPECT_LE(scaledResidualNorm(*condensed, r.solution), options.residual_tolerance);
  // It says where it came from.
  EXPECT_NE(describeFallbacks(report).find("from omega = "), std::string::npos) << describeFallbacks(report);
  // The sweep from the scene's start reaches 0.7 on its grid (101 points).
  ContinuationOptions sweep;
  sweep.from = 0.3;
  sweep.to = 0.7;
  sweep.step = 0.004;
  const Curve curve = sweepSequential(scene.model, *solver, options, sweep);
  ASSERT_TRUE(curve.complete) << curve.stop_reason;
  const CurvePoint& reference = curve.points.back();
  ASSERT_NEAR(reference.omega, 0.7, 1e-12);
  const CurvePoint answer = describePoint(at, condensed->fullCoefficients(r.solution));
  ASSERT_EQ(answer.max_abs.size(), reference.max_abs.size());
  for (size_t i = 0; i < answer.max_abs.size(); ++i)
    EXPECT_NEAR(answer.max_abs[i], reference.max_abs[i], 1e-8 * reference.max_abs[i]) << "DOF " << i;
}

}  // namespace
}  // namespace eqhb
