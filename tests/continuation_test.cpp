#include "eqhb/continuation/continuation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <optional>

#include "eqhb/continuation/arclength_steps.h"
#include "eqhb/continuation/bordered_system.h"
#include "eqhb/continuation/coarse_start.h"
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

// The default options over [from, to], with this step when given.
ContinuationOptions over(double from, double to, std::optional<double> step = std::nullopt) {
  ContinuationOptions options;
  options.from = from;
  options.to = to;
  if (step) options.step = *step;
  return options;
}

// The default options over a scene's own [sweep] range.
ContinuationOptions overItsRange(const Scene& scene) { return over(*scene.sweep_from, *scene.sweep_to); }

// A shipped problem's arclength sweep by the own dogleg on the default
// options over [from, to].
Curve arclengthOver(const std::string& problem, double from, double to) {
  const Scene scene = loadScene(test::problem(problem));
  auto solver = makeSolver("dogleg");
  return sweepArclength(scene.model, *solver, {}, over(from, to));
}

// The same over the scene's own [sweep] range.
Curve arclengthOverItsRange(const std::string& problem) {
  const Scene scene = loadScene(test::problem(problem));
  auto solver = makeSolver("dogleg");
  return sweepArclength(scene.model, *solver, {}, overItsRange(scene));
}

// Warm-started points on the dense LU dogleg: the Jacobian at each accepted
// iterate (its Newton step by GMRES on the LU kept) converges in fewer steps
// than Broyden's updates of the first Jacobian, onto the same curve
// (`eqhb sweep problems/friction-1d.toml --option factorisation=lu`: a median
// of 3 steps per point against 5; beam-joint-large, LU by default at 700
// unknowns: 4 against 11).
TEST(Continuation, TheRefreshModelNeedsFewerStepsPerPointThanSecantUpdates) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"));
  auto solver = makeSolver("dogleg");
  const ContinuationOptions options = overItsRange(scene);
  SolverOptions refresh, broyden;
  refresh.backend = {{"factorisation", "lu"}, {"update", "refresh"}};
  broyden.backend = {{"factorisation", "lu"}, {"update", "broyden"}};
  const Curve a = sweepSequential(scene.model, *solver, refresh, options);
  const Curve b = sweepSequential(scene.model, *solver, broyden, options);
  ASSERT_TRUE(a.complete) << a.stop_reason;
  ASSERT_TRUE(b.complete) << b.stop_reason;
  ASSERT_EQ(a.points.size(), b.points.size());
  auto median = [](const Curve& c) {
    std::vector<int> steps;
    for (const auto& p : c.points) steps.push_back(p.iterations);
    std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
    return steps[steps.size() / 2];
  };
  EXPECT_LT(median(a), median(b)) << "broyden: " << median(b) << ", refresh: " << median(a);
  for (size_t i = 0; i < a.points.size(); ++i)
    EXPECT_NEAR(a.points[i].max_abs.back(), b.points[i].max_abs.back(), 1e-8 * (1 + b.points[i].max_abs.back()))
        << "at omega = " << a.points[i].omega;
}

TEST(Continuation, Friction1dSweepIsContinuousAndPeaksAtTheFirstMode) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"));
  auto solver = makeSolver("dogleg");
  const ContinuationOptions options = over(0.1, 0.8, 0.005);
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
  ContinuationOptions up = over(0.2, 0.5, 0.01);
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
  const Curve curve = arclengthOver("cubic.toml", 0.4, 2.0);
  ASSERT_TRUE(curve.complete) << curve.stop_reason;
  // Hardening: the resonance bends right, turns back (fold), turns again
  // (fold) and the curve ends on the low-amplitude branch.
  ASSERT_GE(curve.fold_omegas.size(), 2u);
  EXPECT_GT(curve.fold_omegas[0], curve.fold_omegas[1]);
  // x1 carries the resonance (the spring on x2 hardens it).
  double peak = 0.0;
  for (const auto& p : curve.points) peak = std::max(peak, p.max_abs[0]);
  EXPECT_LT(curve.points.back().max_abs[0], 0.1 * peak);
  EXPECT_EQ(curve.points.back().omega, 2.0);  // on the end of the range, not beyond it
  // The turning points are passed, not stepped over: ω goes back between the folds.
  bool went_back = false;
  for (size_t i = 1; i < curve.points.size(); ++i) went_back |= curve.points[i].omega < curve.points[i - 1].omega;
  EXPECT_TRUE(went_back);
}

TEST(Continuation, ArclengthAgreesWithSequentialWhereTheCurveIsSingleValued) {
  const Scene scene = loadScene(test::problem("cubic.toml"));
  auto solver = makeSolver("dogleg-newton");
  const ContinuationOptions options = over(0.4, 0.9, 0.01);
  const Curve arc = sweepArclength(scene.model, *solver, {}, options);
  ASSERT_FALSE(arc.points.empty());
  for (const auto& p : arc.points) {
    if (p.omega > 0.9) break;
    HbModel m = scene.model;
    m.omega = p.omega;
    ContinuationOptions single = over(p.omega, p.omega + 1e-3, 1e-3);
    // A plain solve with ω fixed, started 2 % off the arclength point (from
    // rest it does not converge by the superharmonic resonance near 0.56).
    single.start_full = 1.02 * p.full;
    const Curve one = sweepSequential(m, *solver, {}, single);
    ASSERT_TRUE(one.points[0].converged) << "omega " << p.omega << ": " << one.points[0].termination;
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
  ContinuationOptions options = over(0.1, 0.10003, 1e-9);
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

// A stop asked from outside (the command line's signal handler) after the
// third point: both methods keep the three points, are not complete and say
// why and where; the sequential sweep counts the grid points not reached.
TEST(Continuation, AStopRequestKeepsThePointsFound) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"), {"harmonic_balance.harmonics=3",
                                                                      "harmonic_balance.samples=64"});
  auto solver = makeSolver("dogleg");
  for (const bool arclength : {false, true}) {
    std::atomic<bool> requested{false};
    ContinuationOptions options = overItsRange(scene);
    options.stop.requested = &requested;
    int seen = 0;
    const Progress stop_after_three = [&](const CurvePoint&, int) {
      if (++seen == 3) requested.store(true);
    };
    const Curve curve = arclength ? sweepArclength(scene.model, *solver, {}, options, stop_after_three)
                                  : sweepSequential(scene.model, *solver, {}, options, stop_after_three);
    EXPECT_EQ(curve.points.size(), 3u) << (arclength ? "arclength" : "sequential");
    EXPECT_FALSE(curve.complete);
    EXPECT_EQ(curve.failed_points, 0);
    EXPECT_NE(curve.stop_reason.find("stopped on request"), std::string::npos) << curve.stop_reason;
    for (const CurvePoint& p : curve.points) EXPECT_TRUE(p.converged);
    if (!arclength)
      EXPECT_NE(curve.stop_reason.find("before omega = " + formatNumber(curve.points.back().omega + options.step)),
                std::string::npos)
          << curve.stop_reason;
  }
}

// A whole-curve limit already passed: the first point is still solved (the
// curve says where it began), then the curve stops naming the limit.
TEST(Continuation, ACurveTimeLimitStopsAfterTheFirstPoint) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"), {"harmonic_balance.harmonics=3",
                                                                      "harmonic_balance.samples=64"});
  auto solver = makeSolver("dogleg");
  for (const bool arclength : {false, true}) {
    ContinuationOptions options = overItsRange(scene);
    options.stop.deadline = Deadline(1e-9);
    const Curve curve = arclength ? sweepArclength(scene.model, *solver, {}, options)
                                  : sweepSequential(scene.model, *solver, {}, options);
    ASSERT_EQ(curve.points.size(), 1u) << (arclength ? "arclength" : "sequential");
    EXPECT_TRUE(curve.points[0].converged);
    EXPECT_FALSE(curve.complete);
    EXPECT_NE(curve.stop_reason.find("curve_time_limit of 1e-09 s reached"), std::string::npos) << curve.stop_reason;
  }
}

// The Duffing oscillator's response grows tenfold from the start of the
// sweep to its fold. With the unknowns scaled by the first point's
// magnitude, a step that was small at the start stayed as small at the
// peak: the condensed system hit 20000 points at omega = 1.12.
TEST(Continuation, ArclengthTracesTheDuffingCurveInFewPointsOnBothSystems) {
  const Scene scene = loadScene(test::problem("duffing.toml"));
  auto solver = makeSolver("dogleg");
  for (const bool condensed : {true, false}) {
    ContinuationOptions options = overItsRange(scene);
    options.condensed = condensed;
    options.max_points = 400;
    const Curve curve = sweepArclength(scene.model, *solver, {}, options);
    SCOPED_TRACE(condensed ? "condensed" : "full");
    ASSERT_TRUE(curve.complete) << curve.stop_reason << " after " << curve.points.size() << " points";
    EXPECT_EQ(curve.points.back().omega, 1.6);
    // Hardening: the upper fold (jump down) lies right of the lower one (jump up).
    ASSERT_EQ(curve.fold_omegas.size(), 2u);
    EXPECT_NEAR(curve.fold_omegas[0], 1.27, 0.01);
    EXPECT_NEAR(curve.fold_omegas[1], 1.116, 0.01);
    for (const auto& p : curve.points) EXPECT_TRUE(p.omega >= 0.5 && p.omega <= 1.6) << p.omega;
  }
}

// Downwards the curve used to reach the resonance, turn back at a spurious
// fold and leave the range at its start, reported as complete.
TEST(Continuation, ArclengthSweepsDownwardsAndEndsOnTheEndOfTheRange) {
  const Curve curve = arclengthOver("friction-1d.toml", 0.8, 0.1);
  ASSERT_TRUE(curve.complete) << curve.stop_reason;
  EXPECT_EQ(curve.points.back().omega, 0.1);
  EXPECT_TRUE(curve.fold_omegas.empty());  // Coulomb friction on this chain: a single-valued curve
  for (const auto& p : curve.points) EXPECT_TRUE(p.omega >= 0.1 && p.omega <= 0.8) << p.omega;
  EXPECT_NEAR(peakOmega(curve, 1), 0.618, 0.01);
}

// The damper's curve used to turn back at omega = 0.98 on a tangent that
// jumped (a spurious fold) and leave the range at 0.77, reported as complete.
TEST(Continuation, ArclengthDoesNotTurnBackAtASpuriousFold) {
  const Curve curve = arclengthOver("damper.toml", 0.8, 1.4);
  for (double fold : curve.fold_omegas) EXPECT_GT(std::abs(fold - 0.98), 0.01) << curve.stop_reason;
  if (curve.complete) {
    EXPECT_EQ(curve.points.back().omega, 1.4);
  } else {
    EXPECT_NE(curve.stop_reason.find("omega = "), std::string::npos) << curve.stop_reason;
  }
  for (const auto& p : curve.points) EXPECT_TRUE(p.omega >= 0.8 && p.omega <= 1.4) << p.omega;
}

// NLvib's example 03 as posed (a unilateral spring k = 100 at gap 1): the
// contact closes at ω = 0.6534 and the curve turns back at once, a fold with
// no smooth turn. The condensed unknowns (the contact force) are all zero
// before it, so no point lies ahead of the last one there: the sweep went on
// on the full system, where the curve turned back at a kink and was taken
// for a spurious fold; it stopped after 14 points. Now complete, with that
// fold and the resonance's own (past the peak's tip, the upper branch).
TEST(Continuation, ArclengthFollowsAContactThatClosesIntoAFold) {
  const Curve curve = arclengthOverItsRange("field/nlvib-03-unilateral-spring.toml");
  ASSERT_TRUE(curve.complete) << curve.stop_reason << " after " << curve.points.size() << " points";
  EXPECT_NE(curve.stop_reason.find("full system"), std::string::npos) << curve.stop_reason;
  ASSERT_EQ(curve.fold_omegas.size(), 2u) << curve.stop_reason;
  EXPECT_NEAR(curve.fold_omegas[0], 0.6534, 1e-3);  // the contact closes
  EXPECT_NEAR(curve.fold_omegas[1], 0.7556, 1e-3);  // the peak's tip
  EXPECT_GT(curve.points.size(), 100u);
  EXPECT_NEAR(peakOmega(curve, 1), 0.7536, 2e-3);
  double peak = 0.0;
  for (const auto& p : curve.points) peak = std::max(peak, p.max_abs[1]);
  EXPECT_NEAR(peak, 1.238, 2e-3);
}

// NLvib's example 07 with its grounded elastic dry friction, in the AFT form
// it takes by default (as NLvib computes it): the arclength sweep reaches
// the end of the range; the equality form's kinks stopped it at 0.678.
TEST(Continuation, ArclengthCrossesNlvib07WithElasticFrictionByDefault) {
  const Curve curve = arclengthOverItsRange("field/nlvib-07-grounded-jenkins-cubic.toml");
  ASSERT_TRUE(curve.complete) << curve.stop_reason << " after " << curve.points.size() << " points";
  EXPECT_EQ(curve.points.back().omega, 2.0);
}

// Past Duffing's upper fold the branch the sequential sweep followed ends:
// from the previous point the dogleg stalls (12 points lost), the fallback
// chain's cold start finds the remaining branch, and the whole grid converges
// on the same amplitudes wherever the previous point's start was enough.
TEST(Continuation, SequentialPointsLostPastAFoldAreFoundByTheFallbackChain) {
  const Scene scene = loadScene(test::problem("duffing.toml"));
  auto solver = makeSolver("dogleg");
  ContinuationOptions options = overItsRange(scene);
  ContinuationOptions alone = options;
  alone.fallbacks = FallbackChain();
  const Curve lost = sweepSequential(scene.model, *solver, {}, alone);
  const Curve found = sweepSequential(scene.model, *solver, {}, options);
  EXPECT_GT(lost.failed_points, 0);
  EXPECT_EQ(found.failed_points, 0) << found.stop_reason;
  EXPECT_TRUE(found.complete);
  ASSERT_EQ(lost.points.size(), found.points.size());
  int cold = 0;
  for (size_t i = 0; i < found.points.size(); ++i) {
    const CurvePoint &a = lost.points[i], &b = found.points[i];
    ASSERT_TRUE(b.converged) << b.omega;
    if (!b.fallback.empty()) {
      EXPECT_EQ(b.fallback, "cold");
      ++cold;
      // The branch it found lies below the one that ended: a jump down.
      EXPECT_LT(b.max_abs[0], found.points[i - 1].max_abs[0]) << b.omega;
      // And it is the answer at the grid point itself (past the fold the
      // lower branch is the only one): a solve there from rest agrees.
      HbModel at = scene.model;
      at.omega = b.omega;
      auto alone = makeHbSystem(at, true);
      const SolverResult r = CoarseStart(at, true, LinearAlgebra::kAuto).solve(*solver, *alone, {}, nullptr);
      ASSERT_TRUE(r.converged()) << b.omega;
      EXPECT_NEAR(describePoint(at, alone->fullCoefficients(r.solution)).max_abs[0], b.max_abs[0], 1e-9) << b.omega;
    }
    if (a.converged && b.fallback.empty() && i > 0 && found.points[i - 1].fallback.empty()) {
      EXPECT_NEAR(a.max_abs[0], b.max_abs[0], 1e-9) << a.omega;
    }
  }
  EXPECT_GE(cold, 1);
}

TEST(ArclengthSteps, StepFollowsEffortAndTurnWithinItsBounds) {
  ContinuationOptions options;
  options.step = 0.01;
  options.min_step = 0.004;
  options.max_step = 0.05;
  ArclengthStep step(options);
  step.accept(1, 0.0);  // easy and straight: doubles
  EXPECT_DOUBLE_EQ(step.size(), 0.02);
  step.accept(options.target_iterations, options.max_turn);  // turned twice the target: halves
  EXPECT_DOUBLE_EQ(step.size(), 0.01);
  for (int i = 0; i < 5; ++i) step.accept(1, 0.0);
  EXPECT_DOUBLE_EQ(step.size(), 0.05);  // capped at max_step
  EXPECT_TRUE(step.halve());
  EXPECT_TRUE(step.halve());
  EXPECT_TRUE(step.halve());  // 0.00625
  EXPECT_FALSE(step.halve());  // 0.003125 < min_step
  EXPECT_DOUBLE_EQ(step.size(), 0.00625);
}

TEST(ArclengthSteps, AKinkIsATurnThatDoesNotShrinkWithTheStep) {
  KinkTest smooth;
  EXPECT_FALSE(smooth.isKink(0.08, 0.8));
  EXPECT_FALSE(smooth.isKink(0.04, 0.4));
  EXPECT_FALSE(smooth.isKink(0.02, 0.2));
  KinkTest kink;
  EXPECT_FALSE(kink.isKink(0.08, 0.8));
  EXPECT_FALSE(kink.isKink(0.04, 0.7));  // not yet quartered
  EXPECT_TRUE(kink.isKink(0.02, 0.7));
}

TEST(ArclengthSteps, AFoldIsAReversalThatHolds) {
  FoldWatch watch(3);
  EXPECT_EQ(watch.watch(0.5, 0), -1);
  EXPECT_EQ(watch.watch(-0.1, 1), -1);  // flicker
  EXPECT_EQ(watch.watch(0.2, 2), -1);
  EXPECT_EQ(watch.watch(-0.1, 3), -1);
  EXPECT_EQ(watch.watch(-0.2, 4), -1);
  EXPECT_EQ(watch.watch(-0.3, 5), 3);
  EXPECT_EQ(watch.direction(), -1.0);
}

TEST(ArclengthSteps, ARetraceLiesOnThePathANewBranchOffIt) {
  TracedPath path;
  for (int i = 0; i < 4; ++i) path.add(Eigen::VectorXd::Constant(1, 0.1 * i), 1.0 - 0.1 * i);  // (z, ω)
  ArcScales unit;
  Eigen::VectorXd last(2), back(2), away(2);
  last << 0.3, 0.7;
  back << 0.25, 0.75;  // halfway back along the last segment
  away << 0.35, 0.75;  // ω back up, z on: off the path by 0.07 for a move of 0.07
  EXPECT_TRUE(path.retraces(unit, last, back));
  EXPECT_FALSE(path.retraces(unit, last, away));
  path.clear();
  EXPECT_FALSE(path.retraces(unit, last, back));
}

// A bridge asks of the whole curve: a path that keeps every point finds a
// landing on its first segment, 600 points back, which the last 512 (what a
// kink looks at) no longer hold; a bridge's own jump is no part of the path.
TEST(ArclengthSteps, ABridgeLandingFarBackLiesOnTheWholePathNotOnAJump) {
  TracedPath recent, whole(1000);
  for (int i = 0; i < 600; ++i) {
    const Eigen::VectorXd z = Eigen::VectorXd::Constant(1, 0.001 * i);
    recent.add(z, 1.0 + 0.001 * i);
    whole.add(z, 1.0 + 0.001 * i);
  }
  ArcScales unit;
  Eigen::VectorXd last(2), first_segment(2);
  last << 0.0005, 1.1;              // off the path, near its start
  first_segment << 0.0005, 1.0005;  // on the segment from point 0 to point 1
  EXPECT_FALSE(recent.retraces(unit, last, first_segment));
  EXPECT_TRUE(whole.retraces(unit, last, first_segment));

  TracedPath bridged(10);
  bridged.add(Eigen::VectorXd::Constant(1, 0.0), 1.0);
  bridged.add(Eigen::VectorXd::Constant(1, 0.1), 1.1);
  bridged.breakPath();  // jump from (0.1, 1.1) to (0.5, 1.5)
  bridged.add(Eigen::VectorXd::Constant(1, 0.5), 1.5);
  bridged.add(Eigen::VectorXd::Constant(1, 0.6), 1.6);
  Eigen::VectorXd on_jump(2), from(2);
  on_jump << 0.3, 1.3;
  from << 0.3, 2.3;
  EXPECT_FALSE(bridged.retraces(unit, from, on_jump));
  Eigen::VectorXd on_path(2);
  on_path << 0.55, 1.55;
  EXPECT_TRUE(bridged.retraces(unit, from, on_path));
}

TEST(Continuation, StepBoundsAreValidated) {
  ContinuationOptions options;
  options.min_step = 0.5;
  options.max_step = 0.1;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.max_step = NAN;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.min_step = 0.0;
  EXPECT_THROW(options.validate(), InputError);
}

}  // namespace
}  // namespace eqhb
