// The coarse cold start: its rung, that it finds the zero start's solution
// with fewer fine iterations, and its fallback to zero.
#include <gtest/gtest.h>

#include "eqhb/backends/registry.h"
#include "eqhb/continuation/coarse_start.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

TEST(CoarseStart, RungIsAThirdOfTheHarmonicsOnFewSamples) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"));  // H = 10 odd, N = 1024
  const HbModel coarse = coarseModel(scene.model);
  EXPECT_EQ(coarse.basis.kind(), HarmonicKind::kOdd);
  EXPECT_EQ(coarse.basis.count(), 3);    // harmonics 1, 3, 5
  EXPECT_EQ(coarse.samples, 32);         // >= 4 × 5, a power of two
  EXPECT_EQ(coarse.omega, scene.model.omega);
  // Too few harmonics for a coarser rung: the model itself, and no coarse system.
  const Scene small = loadScene(test::problem("friction-1d.toml"), {"harmonic_balance.harmonics=3"});
  EXPECT_EQ(coarseModel(small.model).basis.count(), 3);
  EXPECT_FALSE(CoarseStart(small.model, true, LinearAlgebra::kAuto).available());
  // Never more samples than the fine problem: H = 28 odd (k_max 55) on 112
  // samples has a rung of 9 harmonics (k_max 17) that would take 128.
  const Scene few = loadScene(test::problem("friction-1d.toml"),
                              {"harmonic_balance.harmonics=28", "harmonic_balance.samples=112"});
  EXPECT_EQ(coarseModel(few.model).basis.count(), 9);
  EXPECT_EQ(coarseModel(few.model).samples, 112);
}

TEST(CoarseStart, FindsTheZeroStartsSolutionInFewerFineIterations) {
  for (const char* file : {"friction-1d.toml", "friction-2d.toml", "cubic.toml"}) {
    const Scene scene = loadScene(test::problem(file));
    auto solver = makeSolver("dogleg");
    CondensedSystem system(scene.model);
    const SolverResult from_zero = solver->solve(system, Eigen::VectorXd::Zero(system.size()), {});
    ASSERT_TRUE(from_zero.converged()) << file;
    CoarseStart start(scene.model, true, LinearAlgebra::kAuto);
    ASSERT_TRUE(start.available()) << file;
    ColdStartReport report;
    const SolverResult seeded = start.solve(*solver, system, {}, &report);
    ASSERT_TRUE(seeded.converged()) << file << ": " << seeded.summary();
    EXPECT_TRUE(report.used);
    EXPECT_TRUE(report.coarse.converged()) << file;
    EXPECT_FALSE(report.retried_from_zero) << file;
    EXPECT_LT(seeded.iterations, from_zero.iterations) << file;
    const Eigen::VectorXd a = system.fullCoefficients(seeded.solution), b = system.fullCoefficients(from_zero.solution);
    EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-8 * b.cwiseAbs().maxCoeff()) << file;
  }
}

TEST(CoarseStart, FallsBackToZeroWhenTheSolveFromItFails) {
  // contact.toml (condensed): the coarse rung converges in 16 iterations, the
  // fine solve needs 31 from it and 29 from zero; a limit of 20 lets the
  // rung converge and stops both fine solves.
  const Scene scene = loadScene(test::problem("contact.toml"));
  auto solver = makeSolver("dogleg");
  CondensedSystem system(scene.model);
  CoarseStart start(scene.model, true, LinearAlgebra::kAuto);
  SolverOptions options;
  options.max_iterations = 20;
  const SolverResult from_zero = solver->solve(system, Eigen::VectorXd::Zero(system.size()), options);
  ASSERT_FALSE(from_zero.converged());
  ColdStartReport report;
  const SolverResult result = start.solve(*solver, system, options, &report);
  ASSERT_TRUE(report.coarse.converged()) << report.coarse.summary();
  EXPECT_TRUE(report.retried_from_zero);
  EXPECT_EQ(report.first_attempt.termination, Termination::kIterationLimit);
  // The result is the zero start's own.
  EXPECT_EQ(result.iterations, from_zero.iterations);
  EXPECT_EQ(result.final_norm, from_zero.final_norm);
  // A rung that does not converge is skipped: the fine solve starts at zero.
  options.max_iterations = 5;
  const SolverResult zero5 = solver->solve(system, Eigen::VectorXd::Zero(system.size()), options);
  const SolverResult skipped = start.solve(*solver, system, options, &report);
  EXPECT_FALSE(report.coarse.converged());
  EXPECT_FALSE(report.retried_from_zero);
  EXPECT_EQ(skipped.final_norm, zero5.final_norm);
}

}  // namespace
}  // namespace eqhb
