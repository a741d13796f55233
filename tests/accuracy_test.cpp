// The error estimate (one more solve at 2H) and the accuracy-targeted choice
// of H, against the true error measured on the exact periodic orbit found by
// shooting.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "eqhb/accuracy/accuracy_target.h"
#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/scenes/scene.h"
#include "accuracy_solver_options.h"
#include "test_support.h"

namespace eqhb {
namespace {

struct Solved {
  HbModel model;
  Eigen::VectorXd full;
};

Solved solve(const HbModel& scene_model, int harmonics, Solver& solver, const SolverOptions& options) {
  Solved s{withHarmonics(scene_model, harmonics), {}};
  auto system = makeHbSystem(s.model, true);
  const SolverResult r = solver.solve(*system, Eigen::VectorXd::Zero(system->size()), options);
  EXPECT_TRUE(r.converged()) << "H = " << harmonics;
  s.full = system->fullCoefficients(r.solution);
  return s;
}

// max|x_i| of the exact orbit, shot from a harmonic-balance solution.
Eigen::VectorXd exactMaxAbs(const Solved& hb) {
  const auto flow = orbits::makeFlow(hb.model, 0.0);
  const auto orbit = orbits::shootFromHarmonicBalance(*flow, hb.model, hb.full, orbits::ShootingOptions());
  EXPECT_TRUE(orbit.converged) << orbit.failure;
  return orbit.max_abs;
}

double trueError(const Solved& hb, const Eigen::VectorXd& exact) {
  return worstRelativeDifference(peakDisplacements(hb.model, hb.full), exact);
}

using test::tightOptions;

HbModel scene(const std::string& file, double omega) {
  return loadScene(test::problem(file), {"harmonic_balance.omega=" + formatNumber(omega)}).model;
}

TEST(ErrorEstimate, WithinFactorThreeOfTheExactOrbitError) {
  auto solver = makeSolver("dogleg");
  const SolverOptions options = tightOptions();
  for (const auto& [file, omega, harmonics] :
       {std::tuple{"coulomb-oscillator.toml", 0.6, 5}, std::tuple{"coulomb-oscillator.toml", 0.6, 20},
        std::tuple{"friction-1d.toml", 0.4, 10}, std::tuple{"friction-1d.toml", 0.55, 20},
        std::tuple{"cubic.toml", 0.5, 5}}) {
    const Solved hb = solve(scene(file, omega), harmonics, *solver, options);
    const double truth = trueError(hb, exactMaxAbs(hb));
    const ErrorEstimate e = estimateError(hb.model, hb.full, *solver, options, true);
    ASSERT_TRUE(e.available) << file;
    EXPECT_EQ(e.refined_harmonics, 2 * harmonics);
    EXPECT_GT(truth, 1e-9) << file << " H = " << harmonics << ": the true error must be above rounding";
    EXPECT_GT(e.max_abs / truth, 1.0 / 3) << file << " H = " << harmonics << ": estimate " << e.max_abs
                                          << ", true " << truth;
    EXPECT_LT(e.max_abs / truth, 3.0) << file << " H = " << harmonics << ": estimate " << e.max_abs << ", true "
                                      << truth;
    EXPECT_NEAR(e.max_abs, kDifferenceFactor * e.max_abs_difference, 1e-15);
  }
}

TEST(ErrorEstimate, SpectralForASmoothLaw) {
  // Cubic stiffness: the series converges spectrally; at H = 10 the estimate
  // is at rounding, at H = 5 it is not.
  auto solver = makeSolver("dogleg");
  const SolverOptions options = tightOptions();
  const HbModel cubic = scene("cubic.toml", 0.5);
  const Solved coarse = solve(cubic, 5, *solver, options), fine = solve(cubic, 10, *solver, options);
  EXPECT_GT(estimateError(coarse.model, coarse.full, *solver, options, true).max_abs, 1e-8);
  EXPECT_LT(estimateError(fine.model, fine.full, *solver, options, true).max_abs, 1e-12);
}

TEST(ErrorEstimate, SamplesFollowHarmonicsAndADofAtRestUsesTheFloor) {
  const HbModel m = scene("friction-1d.toml", 0.4);  // H = 10 odd (k_max 19), N = 1024
  const HbModel doubled = withHarmonics(m, 20);
  EXPECT_EQ(doubled.basis.count(), 20);
  EXPECT_EQ(doubled.samples, 2102);  // 1024 · 39/19 rounded up to even
  EXPECT_GE(withHarmonics(m, 1).samples, withHarmonics(m, 1).basis.minimumSamples());
  Eigen::VectorXd reference(2), value(2);
  reference << 1.0, 0.0;
  value << 1.0, 1e-5;  // DOF 2 at rest: 1e-5 against 1e-3 of the largest
  EXPECT_NEAR(worstRelativeDifference(value, reference), 1e-2, 1e-15);
}

// The estimate's test (AccuracyTestChoice::kEstimate): the safety factor
// times the estimate, each rung checked by its solve at 2H.
const AccuracyTestOptions kByEstimate{AccuracyTestChoice::kEstimate};

TEST(AccuracyTarget, ChoosesTheFirstRungWhoseEstimateMeetsTheTolerance) {
  auto solver = makeSolver("dogleg");
  const SolverOptions options = tightOptions();
  const HbModel m = scene("coulomb-oscillator.toml", 0.6);
  const double tolerance = 5e-3;
  const AccuracyChoice c = chooseHarmonics(m, tolerance, 5, 320, *solver, options, true, kByEstimate);
  ASSERT_TRUE(c.reached) << c.failure;
  const int chosen = c.model.basis.count();
  EXPECT_EQ(c.test, AccuracyTest::kEstimate);
  EXPECT_DOUBLE_EQ(c.error, kEstimateSafetyFactor * c.estimate.max_abs);
  EXPECT_LE(c.error, tolerance);
  // Rungs 5, 10, ... up to the chosen one, then its check at 2H.
  ASSERT_GE(c.ladder.size(), 2u);
  EXPECT_EQ(c.ladder.back().harmonics, 2 * chosen);
  EXPECT_FALSE(c.ladder.back().tested);
  for (size_t i = 0; i + 2 < c.ladder.size(); ++i) {
    EXPECT_TRUE(c.ladder[i].estimated && c.ladder[i].tested);
    EXPECT_GT(c.ladder[i].error, tolerance) << "H = " << c.ladder[i].harmonics << " was enough";
  }
  // Against the exact orbit the chosen H meets the tolerance (the safety
  // factor takes it one doubling above the H where the true error of 3.3e-3
  // first met it).
  const Solved at{c.model, c.full};
  EXPECT_LE(trueError(at, exactMaxAbs(at)), tolerance);
  ASSERT_GT(chosen, 5);
}

HbModel withRho(const std::string& file, double omega, double rho) {
  return loadScene(test::problem(file), {"harmonic_balance.omega=" + formatNumber(omega), "law[0].rho=" + formatNumber(rho)})
      .model;
}

TEST(AccuracyTarget, ChoosingRhoReachesTheToleranceOnFewerHarmonics) {
  // friction-1d at ω = 0.4: ρ = 1 needs H = 80 for 3e-3, ρ = 0.1 or 0.01 H = 40.
  auto solver = makeSolver("dogleg");
  const SolverOptions options = tightOptions();
  const double tolerance = 3e-3;
  const std::vector<HbModel> candidates = {withRho("friction-1d.toml", 0.4, 1.0), withRho("friction-1d.toml", 0.4, 0.1),
                                           withRho("friction-1d.toml", 0.4, 0.01)};
  const AccuracyChoice c = chooseDiscretisation(candidates, tolerance, 5, 320, *solver, options, true);
  ASSERT_TRUE(c.reached) << c.failure;
  const int chosen = c.model.basis.count();
  EXPECT_EQ(c.test, AccuracyTest::kExactOrbit);
  EXPECT_LE(c.error, tolerance);
  ASSERT_EQ(c.candidate_ladders.size(), 3u);
  EXPECT_EQ(c.ladder.size(), c.candidate_ladders[c.candidate].size());
  // No candidate met the tolerance on a lower rung, and none on the chosen
  // rung with a smaller tested error.
  for (const auto& ladder : c.candidate_ladders)
    for (const AccuracyRung& r : ladder) {
      if (!r.tested) continue;
      if (r.harmonics < chosen) {
        EXPECT_GT(r.error, tolerance) << "H = " << r.harmonics;
      } else if (r.harmonics == chosen) {
        EXPECT_GE(r.error, c.error);
      }
    }
  const AccuracyChoice fixed = chooseHarmonics(candidates[0], tolerance, 5, 320, *solver, options, true);
  ASSERT_TRUE(fixed.reached) << fixed.failure;
  EXPECT_NE(c.candidate, 0);
  EXPECT_GT(fixed.model.basis.count(), chosen);
  // Against the exact orbit, the chosen ρ and H meet the tolerance.
  const Solved at{c.model, c.full};
  EXPECT_LT(trueError(at, exactMaxAbs(at)), tolerance);
}

TEST(AccuracyTarget, DropsACandidateMoreThanTwiceTheBestFromH20) {
  // friction-1d at ω = 0.308: at H = 20 the estimates are about 5e-3 (ρ = 1),
  // 3.6e-3 (ρ = 0.1) and 1.1e-3 (ρ = 0.01); the first two stop there.
  auto solver = makeSolver("dogleg");
  const std::vector<HbModel> candidates = {withRho("friction-1d.toml", 0.308, 1.0),
                                           withRho("friction-1d.toml", 0.308, 0.1),
                                           withRho("friction-1d.toml", 0.308, 0.01)};
  const AccuracyChoice c = chooseDiscretisation(candidates, 1e-3, 5, 320, *solver, tightOptions(), true, kByEstimate);
  ASSERT_TRUE(c.reached) << c.failure;
  EXPECT_EQ(c.candidate, 2);
  for (int k : {0, 1}) {
    const auto& ladder = c.candidate_ladders[k];
    ASSERT_GE(ladder.size(), 2u);
    EXPECT_EQ(ladder.back().harmonics, 2 * kPruneFromHarmonics) << k;  // the check of rung 20, then no more
    const AccuracyRung& last = ladder[ladder.size() - 2];
    double best = 1.0;
    for (const auto& r : c.candidate_ladders[2])
      if (r.harmonics == last.harmonics) best = r.error;
    EXPECT_GT(last.error, kPruneFactor * best) << k;
  }
  EXPECT_GT(c.model.basis.count(), kPruneFromHarmonics);
}

TEST(AccuracyTarget, NotReachedBelowTheLargestH) {
  auto solver = makeSolver("dogleg");
  const AccuracyChoice c =
      chooseHarmonics(scene("coulomb-oscillator.toml", 0.6), 1e-5, 5, 20, *solver, tightOptions(), true);
  EXPECT_FALSE(c.reached);
  EXPECT_NE(c.failure.find("max_harmonics = 20"), std::string::npos) << c.failure;
}

TEST(AccuracyTarget, RejectsAToleranceThatIsNotARelativeError) {
  auto solver = makeSolver("dogleg");
  const HbModel m = scene("coulomb-oscillator.toml", 0.6);
  for (double bad : {0.0, -1e-3, 1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()})
    EXPECT_THROW(chooseHarmonics(m, bad, 5, 320, *solver, tightOptions(), true), InputError) << bad;
  EXPECT_THROW(chooseHarmonics(m, 1e-3, 5, 0, *solver, tightOptions(), true), InputError);
  EXPECT_THROW(chooseHarmonics(m, 1e-3, 40, 20, *solver, tightOptions(), true), InputError);
}

}  // namespace
}  // namespace eqhb
