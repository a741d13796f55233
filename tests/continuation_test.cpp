#include "eqhb/continuation/continuation.h"

#include <gtest/gtest.h>

#include "eqhb/error.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/backends/registry.h"
#include "test_support.h"

namespace eqhb {
namespace {

double peakOmega(const Curve& curve, int dof) {
  double best = -1.0, at = 0.0;
  for (const auto& p : curve.points)
    if (p.converged && p.max_abs[dof] > best) best = p.max_abs[dof], at = p.omega;
  return at;
}

TEST(Continuation, Friction1dSweepIsContinuousAndPeaksAtTheFirstMode) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"));
  auto solver = makeSolver("dogleg");
  ContinuationOptions options;
  options.from = 0.1;
  options.to = 0.8;
  options.step = 0.005;
  const Curve curve = sweepSequential(scene.model, *solver, {}, options);
  ASSERT_EQ(curve.failed_points, 0) << curve.stop_reason;
  ASSERT_EQ(curve.points.size(), 141u);
  EXPECT_NEAR(peakOmega(curve, 1), 0.618, 0.01);
  // Continuous: no jump between neighbours larger than a fraction of the local amplitude.
  for (size_t i = 1; i < curve.points.size(); ++i) {
    const double a = curve.points[i - 1].max_abs[1], b = curve.points[i].max_abs[1];
    EXPECT_LT(std::abs(a - b), 0.35 * std::max(a, b)) << "between omega " << curve.points[i - 1].omega << " and "
                                                      << curve.points[i].omega;
  }
}

TEST(Continuation, SweepsUpAndDownAgreeWhereTheResponseIsUnique) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"));
  auto solver = makeSolver("dogleg");
  ContinuationOptions up;
  up.from = 0.2;
  up.to = 0.5;
  up.step = 0.01;
  ContinuationOptions down = up;
  std::swap(down.from, down.to);
  const Curve a = sweepSequential(scene.model, *solver, {}, up);
  const Curve b = sweepSequential(scene.model, *solver, {}, down);
  ASSERT_EQ(a.points.size(), b.points.size());
  const size_t n = a.points.size();
  for (size_t i = 0; i < n; ++i) {
    const CurvePoint& p = a.points[i];
    const CurvePoint& q = b.points[n - 1 - i];
    ASSERT_NEAR(p.omega, q.omega, 1e-12);
    ASSERT_TRUE(p.converged && q.converged);
    EXPECT_LT((p.full - q.full).norm(), 1e-7 * p.full.norm()) << "omega " << p.omega;
  }
}

TEST(Continuation, ArclengthPassesTheFoldsOfTheCubicScene) {
  const Scene scene = loadScene(test::problem("cubic.toml"));
  auto solver = makeSolver("dogleg");
  ContinuationOptions options;
  options.from = 0.4;
  options.to = 2.0;
  const Curve curve = sweepArclength(scene.model, *solver, {}, options);
  ASSERT_TRUE(curve.complete) << curve.stop_reason;
  // Hardening: the resonance bends right, turns back (fold), turns again
  // (fold) and the curve ends on the low-amplitude branch.
  ASSERT_GE(curve.fold_omegas.size(), 2u);
  EXPECT_GT(curve.fold_omegas[0], curve.fold_omegas[1]);
  // x1 carries the resonance (the spring on x2 hardens it).
  double peak = 0.0;
  for (const auto& p : curve.points) peak = std::max(peak, p.max_abs[0]);
  EXPECT_LT(curve.points.back().max_abs[0], 0.1 * peak);
  EXPECT_GT(curve.points.back().omega, 2.0 - 1e-9);
  // The turning points are passed, not stepped over: ω goes back between the folds.
  bool went_back = false;
  for (size_t i = 1; i < curve.points.size(); ++i) went_back |= curve.points[i].omega < curve.points[i - 1].omega;
  EXPECT_TRUE(went_back);
}

TEST(Continuation, ArclengthAgreesWithSequentialWhereTheCurveIsSingleValued) {
  const Scene scene = loadScene(test::problem("cubic.toml"));
  auto solver = makeSolver("dogleg-newton");
  ContinuationOptions options;
  options.from = 0.4;
  options.to = 0.9;
  options.step = 0.01;
  const Curve arc = sweepArclength(scene.model, *solver, {}, options);
  ASSERT_FALSE(arc.points.empty());
  for (const auto& p : arc.points) {
    if (p.omega > 0.9) break;
    HbModel m = scene.model;
    m.omega = p.omega;
    ContinuationOptions single;
    single.from = p.omega;
    single.to = p.omega + 1e-3;
    single.step = 1e-3;
    const Curve one = sweepSequential(m, *solver, {}, single);
    ASSERT_TRUE(one.points[0].converged);
    EXPECT_NEAR(one.points[0].max_abs[1], p.max_abs[1], 1e-6 * p.max_abs[1]) << "omega " << p.omega;
  }
}

TEST(Continuation, HarmonicContinuationReachesLargeH) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"), {"harmonic_balance.harmonics=120",
                                                                    "harmonic_balance.samples=8192"});
  auto solver = makeSolver("dogleg");
  Eigen::VectorXd full;
  const SolverResult r = solveByHarmonicContinuation(scene.model, *solver, {}, 10, true, &full);
  EXPECT_TRUE(r.converged()) << r.summary();
  EXPECT_EQ(full.size(), 3 * scene.model.basis.size());
}

TEST(Continuation, OptionsAreValidated) {
  ContinuationOptions options;
  options.from = -1.0;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.to = options.from;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.step = 0.0;
  EXPECT_THROW(options.validate(), InputError);
}

TEST(Continuation, AGridBeyondMaxPointsIsRefusedUpFront) {
  // It used to stop silently at max_points and report the end of the range.
  const Scene scene = loadScene(test::problem("friction-1d.toml"));
  auto solver = makeSolver("dogleg");
  ContinuationOptions options;
  options.from = 0.1;
  options.to = 0.10003;
  options.step = 1e-9;
  options.min_step = 1e-9;
  EXPECT_NEAR(options.gridPoints(), 30001, 1);
  try {
    sweepSequential(scene.model, *solver, {}, options);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more than max_points = 20000"), std::string::npos) << e.what();
  }
  options.step = 1e-5;  // 4 points
  options.min_step = 1e-6;
  const Curve curve = sweepSequential(scene.model, *solver, {}, options);
  EXPECT_EQ(curve.points.size(), 4u);
  EXPECT_TRUE(curve.complete);
}

TEST(Continuation, ArclengthStoppedByMaxPointsIsNotComplete) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"), {"harmonic_balance.harmonics=3",
                                                                      "harmonic_balance.samples=64"});
  auto solver = makeSolver("dogleg");
  ContinuationOptions options;
  options.max_points = 3;
  const Curve curve = sweepArclength(scene.model, *solver, {}, options);
  EXPECT_EQ(curve.points.size(), 3u);
  EXPECT_FALSE(curve.complete);
  EXPECT_NE(curve.stop_reason.find("max_points = 3 reached"), std::string::npos) << curve.stop_reason;
}

}  // namespace
}  // namespace eqhb
