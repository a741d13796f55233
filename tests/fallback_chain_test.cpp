#include "eqhb/continuation/fallback_chain.h"

#include <gtest/gtest.h>

#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

// A solve of `system` from rest (zero unknowns).
SolverResult solveFromRest(HbSystem& system, Solver& solver, const SolverOptions& options) {
  return solver.solve(system, Eigen::VectorXd::Zero(system.size()), options);
}

// friction-2d with the tanh friction form on the full system: the own dogleg
// stalls from rest (not_progressing, |g| 0.019), and so do its coarse start and
// Ipopt's least squares, while the condensed system converges cold. The
// chain's "condensed" step solves it there and polishes the answer on the
// full system, so the result is a converged solve of the full system itself.
TEST(FallbackChain, AFullSystemThatStallsIsSolvedOnTheCondensedSystem) {
  const Scene scene = loadScene(test::problem("friction-2d.toml"), {"law[0].form=\"tanh\""});
  auto full = makeHbSystem(scene.model, false);
  auto solver = makeSolver("dogleg");
  const SolverOptions options;
  const SolverResult failed = solveFromRest(*full, *solver, options);
  ASSERT_FALSE(failed.converged());

  const FallbackChain without = FallbackChain::parse("cold,full", "fallback", [](const std::string&) { return nullptr; });
  EXPECT_FALSE(solveWithFallbacks(*full, *solver, options, failed, false, without, nullptr).converged());

  const FallbackChain chain = FallbackChain::standard(nullptr);
  FallbackReport report;
  const SolverResult r = solveWithFallbacks(*full, *solver, options, failed, true, chain, &report);
  ASSERT_TRUE(r.converged()) << describeFallbacks(report);
  EXPECT_EQ(report.taken, "condensed");
  // The answer is the full system's: its residual, in its own scales, within tolerance there.
  Eigen::VectorXd g(full->size()), scales(full->size());
  ASSERT_TRUE(full->residual(r.solution, g));
  full->residualScales(scales);
  EXPECT_LE(g.cwiseQuotient(scales).norm(), options.residual_tolerance);
  // And it is the condensed system's solution.
  auto condensed = makeHbSystem(scene.model, true);
  const SolverResult direct = solveFromRest(*condensed, *solver, options);
  ASSERT_TRUE(direct.converged());
  EXPECT_LT((full->fullCoefficients(r.solution) - condensed->fullCoefficients(direct.solution)).norm(),
            1e-6 * condensed->fullCoefficients(direct.solution).norm());
}

// On the condensed system the step has nothing to add and is skipped.
TEST(FallbackChain, TheCondensedStepIsSkippedOnTheCondensedSystem) {
  const Scene scene = loadScene(test::problem("contact.toml"), {"law[0].form=\"sign-square\""});
  auto condensed = makeHbSystem(scene.model, true);
  auto solver = makeSolver("dogleg");
  const SolverOptions options;
  const SolverResult failed = solveFromRest(*condensed, *solver, options);
  ASSERT_FALSE(failed.converged());
  FallbackReport report;
  const FallbackChain chain =
      FallbackChain::parse("condensed", "fallback", [](const std::string&) { return nullptr; });
  solveWithFallbacks(*condensed, *solver, options, failed, true, chain, &report);
  EXPECT_TRUE(report.attempts.empty());
}

TEST(FallbackChain, ParsesTheCondensedStepAndRefusesItTwice) {
  auto none = [](const std::string&) -> Solver* { return nullptr; };
  EXPECT_EQ(FallbackChain::parse("cold,condensed", "fallback", none).steps,
            (std::vector<std::string>{"cold", "condensed"}));
  EXPECT_THROW(FallbackChain::parse("condensed,condensed", "fallback", none), InputError);
  EXPECT_EQ(FallbackChain::standard(nullptr).steps, (std::vector<std::string>{"cold", "full", "condensed"}));
}

}  // namespace
}  // namespace eqhb
