// The foundation's acceptance: friction-1d at ω = 0.4 with H = 10 odd
// harmonics, from a zero initial guess.
#include <gtest/gtest.h>

#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/backends/registry.h"
#include "test_support.h"

namespace eqhb {
namespace {

struct Solved {
  SolverResult result;
  Eigen::VectorXd full;
};

Solved solve(const std::string& solver, bool condensed, const std::vector<std::string>& set = {}) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"), set);
  std::unique_ptr<HbSystem> system;
  if (condensed) system = std::make_unique<CondensedSystem>(scene.model);
  else system = std::make_unique<FullSystem>(scene.model);
  SolverOptions options;
  Solved s;
  s.result = makeSolver(solver)->solve(*system, Eigen::VectorXd::Zero(system->size()), options);
  s.full = system->fullCoefficients(s.result.solution);
  return s;
}

TEST(Friction1d, OwnDoglegConvergesFromZeroOnBothSystems) {
  for (bool condensed : {true, false}) {
    const Solved s = solve("dogleg", condensed);
    ASSERT_TRUE(s.result.converged()) << s.result.summary();
    EXPECT_LE(s.result.final_norm, 1e-10);
    // Regression signal: counts are deterministic (see the closing figures).
    EXPECT_LE(s.result.iterations, condensed ? 40 : 70) << s.result.summary();
    EXPECT_LE(s.result.jacobian_evaluations, 8) << s.result.summary();
  }
}

TEST(Friction1d, FullAndCondensedSystemsGiveTheSameSolution) {
  const Solved full = solve("dogleg", false);
  const Solved condensed = solve("dogleg", true);
  ASSERT_TRUE(full.result.converged());
  ASSERT_TRUE(condensed.result.converged());
  EXPECT_LT((full.full - condensed.full).norm(), 1e-8 * full.full.norm());
}

TEST(Friction1d, EveryFormAndBackendAgreesOnTheExactSolution) {
  const Solved reference = solve("dogleg-newton", true);
  ASSERT_TRUE(reference.result.converged());
  for (const std::string solver : {"dogleg", "dogleg-newton", "minpack"})
    for (const std::string form : {"minmax", "projection"}) {
      if (!test::registered(solver)) continue;
      const Solved s = solve(solver, true, {"law[0].form=" + form});
      ASSERT_TRUE(s.result.converged()) << solver << " " << form << ": " << s.result.summary();
      EXPECT_LT((s.full - reference.full).norm(), 1e-8 * reference.full.norm()) << solver << " " << form;
    }
}

// Every registered backend either solves friction-1d (ω = 0.4, H = 10) from
// zero or says it did not; those that converge agree to 1e-8 relative.
TEST(Friction1d, EveryBackendSolvesOrSaysItDidNot) {
  const Solved reference = solve("dogleg-newton", true);
  ASSERT_TRUE(reference.result.converged());
  int converged = 0;
  for (const auto& entry : registeredSolvers())
    for (bool condensed : {true, false}) {
      const Solved s = solve(entry.name, condensed);
      const std::string label = entry.name + (condensed ? " condensed" : " full");
      if (s.result.converged()) {
        ++converged;
        EXPECT_LE(s.result.final_norm, 1e-10) << label;
        EXPECT_LT((s.full - reference.full).norm(), 1e-8 * reference.full.norm()) << label;
      } else {
        EXPECT_GT(s.result.final_norm, 1e-10) << label << " " << s.result.summary();
        EXPECT_NE(s.result.termination, Termination::kConverged) << label;
      }
    }
  // Own dogleg, Newton-dogleg (and MINPACK when built) on both systems at least.
  EXPECT_GE(converged, test::registered("minpack") ? 6 : 4);
}

TEST(Friction1d, SolutionObeysCoulombWhereItSticksAndSlides) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"));
  const Solved s = solve("dogleg", true);
  ASSERT_TRUE(s.result.converged());
  const HbSolution solution = summarize(scene.model, s.full);
  // The forced response is large (x2 ~ 29) and the friction force saturates
  // at μN = 7.2 apart from the Gibbs overshoot of a truncated square wave.
  EXPECT_GT(solution.displacements[1].max_abs, 20.0);
  EXPECT_GT(solution.forces[0].max_abs, 7.2 * 0.95);
  EXPECT_LT(solution.forces[0].max_abs, 7.2 * 1.2);
}

}  // namespace
}  // namespace eqhb
