#include "eqhb/continuation/failed_runs.h"

#include <gtest/gtest.h>

#include <memory>

#include "eqhb/backends/registry.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

// The Duffing scene, the own dogleg and a sequential sweep from 0.9 to `to`
// by `step`.
struct DuffingSweep {
  Scene scene = loadScene(test::problem("duffing.toml"));
  std::unique_ptr<Solver> solver = makeSolver("dogleg");
  ContinuationOptions options;
  DuffingSweep(double to, double step) {
    options.from = 0.9;
    options.to = to;
    options.step = step;
  }
};

// Its upper branch, every point converged (its folds: 1.2696 on the upper
// branch, 1.1157 on the lower one, by arclength).
Curve upperBranch(double to, double step) {
  DuffingSweep duffing(to, step);
  Curve curve = sweepSequential(duffing.scene.model, *duffing.solver, {}, duffing.options);
  for (const CurvePoint& p : curve.points) EXPECT_TRUE(p.converged) << p.omega;
  return curve;
}

// Forgets point i's answer, as a point that failed from both sides.
void markFailed(Curve* curve, size_t i) {
  CurvePoint& p = curve->points[i];
  p.converged = false;
  p.termination = "not_progressing";
  p.full.resize(0);
  p.max_abs.clear();
  ++curve->failed_points;
}

// Runs the last resort on `curve`, a Duffing sweep from 0.9 to `to` by `step`.
void followAcross(Curve* curve, double to, double step) {
  DuffingSweep duffing(to, step);
  followBranchesAcrossFailedRuns(duffing.scene.model, *duffing.solver, {}, duffing.options, curve);
}

// A point between two converged neighbours of one branch is solved from the
// branch traced by arclength from the point before it: the same answer.
TEST(FailedRuns, APointTheBranchCrossesIsSolvedFromIt) {
  Curve curve = upperBranch(1.2, 0.1);
  ASSERT_EQ(curve.points.size(), 4u);  // 0.9, 1.0, 1.1, 1.2
  const CurvePoint known = curve.points[2];
  ASSERT_GT(known.max_abs[0], 1.0);  // the upper branch: above the jump
  markFailed(&curve, 2);
  followAcross(&curve, 1.2, 0.1);
  const CurvePoint& p = curve.points[2];
  ASSERT_TRUE(p.converged) << p.termination;
  EXPECT_EQ(curve.failed_points, 0);
  EXPECT_EQ(p.fallback.rfind("by arclength from omega = 1", 0), 0u) << p.fallback;
  EXPECT_NEAR(p.max_abs[0], known.max_abs[0], 1e-8 * known.max_abs[0]);
  EXPECT_LT((p.full - known.full).norm(), 1e-7 * known.full.norm());
}

// Past the upper branch's fold there is no point of that branch: the failed
// point keeps its failure and says where its neighbour's branch turned.
TEST(FailedRuns, APointPastTheFoldSaysWhereTheBranchTurns) {
  Curve curve = upperBranch(1.25, 0.05);
  ASSERT_NEAR(curve.points.back().omega, 1.25, 1e-12);
  ASSERT_GT(curve.points.back().max_abs[0], 1.0);
  CurvePoint beyond;
  beyond.omega = 1.3;
  curve.points.push_back(beyond);
  markFailed(&curve, curve.points.size() - 1);
  followAcross(&curve, 1.3, 0.05);
  const CurvePoint& p = curve.points.back();
  EXPECT_FALSE(p.converged);
  EXPECT_EQ(curve.failed_points, 1);
  const std::string expected = "not_progressing (no solution on the neighbour's branch: from omega = 1.25 it folds back at 1.2";
  EXPECT_EQ(p.termination.rfind(expected, 0), 0u) << p.termination;
  const double fold = std::stod(p.termination.substr(expected.size() - 3));
  EXPECT_GT(fold, 1.25);
  EXPECT_LT(fold, 1.3);
}

}  // namespace
}  // namespace eqhb
