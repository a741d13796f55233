// The accuracy target's success test (accuracy/rung_test.h): the true error
// against the exact orbit where every law has an exact flow and the
// structure is small, the estimate times its safety factor elsewhere.
#include <gtest/gtest.h>

#include "eqhb/accuracy/accuracy_target.h"
#include "eqhb/accuracy/rung_test.h"
#include "eqhb/error.h"
#include "eqhb/scenes/scene.h"
#include "accuracy_solver_options.h"
#include "test_support.h"

namespace eqhb {
namespace {

using test::tightOptions;

HbModel scene(const std::string& file, double omega, std::vector<std::string> overrides = {}) {
  overrides.push_back("harmonic_balance.omega=" + formatNumber(omega));
  return loadScene(test::problem(file), overrides).model;
}

// The error of a choice's solution against the exact orbit, shot afresh.
double trueError(const AccuracyChoice& c) {
  const ExactOrbitError exact = exactOrbitError(c.model, c.full);
  EXPECT_TRUE(exact.converged) << exact.failure;
  return exact.error;
}

// friction-1d at ω = 0.35 (ρ = 1), TOL = 1e-3: the errors do not fall
// smoothly there (true error 2.6e-3 at H = 20 and 2.7e-3 at H = 40), and the
// estimate at H = 20 reads 4.7e-4, 5.5 times low.
TEST(AccuracyExactTest, MeetsTheToleranceAgainstTheExactOrbitWhereTheEstimateIsLow) {
  auto solver = makeSolver("dogleg");
  const HbModel m = scene("friction-1d.toml", 0.35);
  const AccuracyChoice c = chooseHarmonics(m, 1e-3, 5, 320, *solver, tightOptions(), true);
  ASSERT_TRUE(c.reached) << c.failure;
  EXPECT_EQ(c.test, AccuracyTest::kExactOrbit);
  EXPECT_TRUE(c.test_note.empty()) << c.test_note;
  EXPECT_LE(c.error, 1e-3);
  EXPECT_LE(trueError(c), 1e-3);
  // Every rung below the chosen one was tested against the exact orbit and
  // missed: the choice is the first H that meets TOL, not a later one.
  for (size_t i = 0; i + 1 < c.ladder.size(); ++i) {
    EXPECT_TRUE(c.ladder[i].tested && c.ladder[i].test == AccuracyTest::kExactOrbit);
    EXPECT_GT(c.ladder[i].error, 1e-3) << "H = " << c.ladder[i].harmonics << " was enough";
  }
  EXPECT_EQ(c.ladder.back().harmonics, c.model.basis.count());
  EXPECT_LE(c.ladder.back().error, 1e-3);
}

// The same case by the estimate with a factor 2 stops at H = 20, where the
// true error is 2.6 times the tolerance: the reason the calibrated factor is
// larger, and the exact test decides where it can.
TEST(AccuracyExactTest, TheEstimateWithFactorTwoWouldMissTheSameCase) {
  auto solver = makeSolver("dogleg");
  const HbModel m = scene("friction-1d.toml", 0.35);
  const AccuracyChoice c = chooseHarmonics(m, 1e-3, 5, 320, *solver, tightOptions(), true,
                                           AccuracyTestOptions{AccuracyTestChoice::kEstimate, 2.0});
  ASSERT_TRUE(c.reached) << c.failure;
  EXPECT_EQ(c.test, AccuracyTest::kEstimate);
  EXPECT_EQ(c.model.basis.count(), 20);
  EXPECT_DOUBLE_EQ(c.error, 2.0 * c.estimate.max_abs);
  EXPECT_GT(trueError(c), 1.5e-3);
  // With the calibrated factor the estimate does not claim H = 20 (on ρ = 1
  // it climbs to max_harmonics without a claim).
  const AccuracyChoice calibrated = chooseHarmonics(m, 1e-3, 5, 320, *solver, tightOptions(), true,
                                                    AccuracyTestOptions{AccuracyTestChoice::kEstimate});
  EXPECT_TRUE(!calibrated.reached || calibrated.model.basis.count() > 20);
  if (calibrated.reached) {
    EXPECT_LE(trueError(calibrated), 1.5e-3);
  }
}

TEST(AccuracyExactTest, LawsWithoutAnExactFlowAreTestedByTheEstimateWithItsSafetyFactor) {
  auto solver = makeSolver("dogleg");
  const HbModel m = scene("field/tmdsimpy-2dof-elastic-dry-friction.toml", 2.0);  // contact-friction: no exact flow
  EXPECT_FALSE(exactOrbitUnavailable(m).empty());
  const AccuracyChoice c = chooseHarmonics(m, 1e-2, 5, 320, *solver, tightOptions(), true);
  ASSERT_TRUE(c.reached) << c.failure;
  EXPECT_EQ(c.test, AccuracyTest::kEstimate);
  EXPECT_EQ(c.test_note, exactOrbitUnavailable(m));
  EXPECT_DOUBLE_EQ(c.error, kEstimateSafetyFactor * c.estimate.max_abs);
  EXPECT_LE(c.error, 1e-2);
}

TEST(AccuracyExactTest, ALargeStructureIsLeftToTheEstimate) {
  const HbModel small = scene("friction-1d.toml", 0.4);
  EXPECT_EQ(exactOrbitUnavailable(small), "");
  const HbModel large =
      scene("friction-1d.toml", 0.4, {"structure.dofs=" + std::to_string(kExactOrbitMaxDofs + 1)});
  EXPECT_NE(exactOrbitUnavailable(large).find("DOFs, above the"), std::string::npos) << exactOrbitUnavailable(large);
}

TEST(AccuracyExactTest, TheExactTestReachesTheLargestHItself) {
  // Coulomb oscillator at ω = 0.6, TOL = 5e-3, H <= 10: the exact test
  // tests H = 10 itself (true error 5.8e-3, not met); the estimate would
  // need a solve at 20 to test 10 and stops at 5.
  auto solver = makeSolver("dogleg");
  const HbModel m = scene("coulomb-oscillator.toml", 0.6);
  const AccuracyChoice exact = chooseHarmonics(m, 5e-3, 5, 10, *solver, tightOptions(), true);
  EXPECT_FALSE(exact.reached);
  EXPECT_EQ(exact.test, AccuracyTest::kExactOrbit);
  EXPECT_EQ(exact.model.basis.count(), 10);
  EXPECT_TRUE(exact.ladder.back().tested);
  EXPECT_GT(exact.error, 5e-3);
  EXPECT_NE(exact.failure.find("exact-orbit error"), std::string::npos) << exact.failure;
  const AccuracyChoice estimate = chooseHarmonics(m, 5e-3, 5, 10, *solver, tightOptions(), true,
                                                  AccuracyTestOptions{AccuracyTestChoice::kEstimate});
  EXPECT_FALSE(estimate.reached);
  EXPECT_EQ(estimate.model.basis.count(), 5);
  EXPECT_NE(estimate.failure.find("x safety factor"), std::string::npos) << estimate.failure;
}

// A penalty wall at ω = 0.5 with k_n = 100: the first rung's solve from zero
// stalls (not_progressing); the default path's steps (here the cold one: the
// coarse start) converge it, and the ladder then climbs to the tolerance
// against the exact orbit. Without a chain the ladder makes no claim.
TEST(AccuracyExactTest, AFirstRungThatFailsFromZeroTakesTheFallbackSteps) {
  auto solver = makeSolver("dogleg");
  const HbModel m = scene("penalty-contact.toml", 0.5, {"law[0].stiffness=100"});
  const AccuracyChoice alone = chooseHarmonics(m, 1e-3, 5, 320, *solver, tightOptions(), true);
  EXPECT_FALSE(alone.reached);
  EXPECT_FALSE(alone.ladder.front().converged);
  EXPECT_NE(alone.failure.find("H = 5 did not converge"), std::string::npos) << alone.failure;
  EXPECT_EQ(alone.failure.find("fallback"), std::string::npos) << alone.failure;

  const FallbackChain chain = FallbackChain::standard(nullptr);
  const AccuracyChoice helped = chooseHarmonics(m, 1e-3, 5, 320, *solver, tightOptions(), true, {}, chain);
  ASSERT_TRUE(helped.reached) << helped.failure;
  EXPECT_TRUE(helped.ladder.front().converged);
  EXPECT_FALSE(helped.ladder.front().fallback.empty());
  EXPECT_EQ(helped.test, AccuracyTest::kExactOrbit);
  EXPECT_LE(trueError(helped), 1e-3);
}

TEST(AccuracyExactTest, NamesTheTestChoice) {
  EXPECT_EQ(parseAccuracyTestChoice("auto"), AccuracyTestChoice::kAuto);
  EXPECT_EQ(parseAccuracyTestChoice("estimate"), AccuracyTestChoice::kEstimate);
  EXPECT_THROW(parseAccuracyTestChoice("exact"), InputError);
  EXPECT_STREQ(accuracyTestName(AccuracyTest::kExactOrbit), "exact-orbit");
}

}  // namespace
}  // namespace eqhb
