// A frequency-response curve to an accuracy target: H chosen at the first
// frequency, raised on the points whose estimate exceeds the tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "eqhb/accuracy/accuracy_sweep.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/scenes/scene.h"
#include "accuracy_solver_options.h"
#include "test_support.h"

namespace eqhb {
namespace {

using test::tightOptions;

ContinuationOptions grid(double from, double to, double step) {
  ContinuationOptions c;
  c.from = from;
  c.to = to;
  c.step = step;
  c.min_step = 1e-6;
  return c;
}

HbModel scene(const std::string& file) { return loadScene(test::problem(file)).model; }

// The true error of a point's solution on the curve's H against the exact
// orbit, computed afresh.
double errorAtCurveH(const AccurateCurve& a, double omega, Solver& solver, const SolverOptions& options) {
  HbModel m = a.model;
  m.omega = omega;
  auto system = makeHbSystem(m, true);
  const SolverResult r = solver.solve(*system, Eigen::VectorXd::Zero(system->size()), options);
  EXPECT_TRUE(r.converged()) << "omega = " << omega;
  const ExactOrbitError exact = exactOrbitError(m, system->fullCoefficients(r.solution));
  EXPECT_TRUE(exact.converged) << exact.failure;
  return exact.error;
}

TEST(AccuracySweep, RaisesHExactlyWhereTheCurvesHMissesTheTolerance) {
  auto solver = makeSolver("dogleg");
  const SolverOptions options = tightOptions();
  const double tolerance = 5e-3;
  const AccurateCurve a = sweepToAccuracy({scene("coulomb-oscillator.toml")}, tolerance, 5, 320, *solver, options,
                                          grid(0.5, 1.0, 0.05), false);
  ASSERT_TRUE(a.first.reached) << a.first.failure;
  EXPECT_TRUE(a.not_met.empty());
  const int curve_h = a.model.basis.count();
  int raised = 0;
  for (const CurvePoint& p : a.curve.points) {
    ASSERT_TRUE(p.converged) << p.omega;
    ASSERT_TRUE(p.accuracy) << p.omega;
    EXPECT_TRUE(p.accuracy->met) << p.omega;
    // The Coulomb oscillator has an exact flow: every point is tested
    // against its exact orbit.
    EXPECT_EQ(p.accuracy->test, "exact-orbit") << p.omega;
    EXPECT_LE(p.accuracy->error, tolerance) << p.omega;
    // H is the curve's times a power of two, and N follows it.
    ASSERT_GE(p.harmonics, curve_h);
    EXPECT_EQ(p.harmonics % curve_h, 0);
    EXPECT_EQ(p.harmonics / curve_h & (p.harmonics / curve_h - 1), 0) << p.harmonics;
    const HbModel at = pointModel(a.model, p);
    EXPECT_EQ(at.samples, p.samples);
    EXPECT_EQ(p.full.size(), at.structure.dofs() * at.basis.size() + at.lawComponents() * at.basis.size());
    const double at_curve_h = errorAtCurveH(a, p.omega, *solver, options);
    if (p.harmonics > curve_h) {
      ++raised;
      EXPECT_GT(at_curve_h, tolerance) << "omega = " << p.omega << ": raised although H = " << curve_h << " met it";
    } else {
      EXPECT_LE(at_curve_h, tolerance) << "omega = " << p.omega << ": not raised";
    }
  }
  EXPECT_GT(raised, 0) << "the test needs a curve on which H must rise";
  EXPECT_EQ(a.highest_harmonics, 20);
}

TEST(AccuracySweep, NamesThePointsWhereTheLargestHIsNotEnough) {
  auto solver = makeSolver("dogleg");
  const AccurateCurve a = sweepToAccuracy({scene("coulomb-oscillator.toml")}, 5e-3, 5, 10, *solver, tightOptions(),
                                          grid(0.5, 1.0, 0.05), false);
  ASSERT_FALSE(a.not_met.empty());
  for (double omega : a.not_met) {
    bool found = false;
    for (const CurvePoint& p : a.curve.points)
      if (p.omega == omega) {
        found = true;
        ASSERT_TRUE(p.accuracy) << p.omega;
        EXPECT_FALSE(p.accuracy->met);
        EXPECT_GT(p.accuracy->error, 5e-3);
        EXPECT_NE(p.accuracy->failure.find("max_harmonics"), std::string::npos) << p.accuracy->failure;
      }
    EXPECT_TRUE(found) << omega;
  }
}

TEST(AccuracySweep, TheCurveStartsFromTheFirstLaddersSolution) {
  // friction-1d at ω = 0.1: the ladder picks ρ = 0.01 and H = 20, on which a
  // cold start does not converge; the curve starts from the ladder's solution.
  auto solver = makeSolver("dogleg");
  std::vector<HbModel> candidates;
  for (const char* rho : {"1", "0.1", "0.01"})
    candidates.push_back(loadScene(test::problem("friction-1d.toml"), {std::string("law[0].rho=") + rho}).model);
  const AccurateCurve a =
      sweepToAccuracy(candidates, 1e-2, 5, 320, *solver, tightOptions(), grid(0.1, 0.12, 0.01), false);
  ASSERT_TRUE(a.first.reached) << a.first.failure;
  EXPECT_EQ(a.curve.failed_points, 0);
  ASSERT_EQ(a.curve.points.size(), 3u);
  for (const CurvePoint& p : a.curve.points) EXPECT_TRUE(p.accuracy && p.accuracy->met) << p.omega;
  EXPECT_TRUE(a.not_met.empty());
}

TEST(AccuracySweep, RejectsAToleranceThatIsNotARelativeErrorBeforeSolving) {
  auto solver = makeSolver("dogleg");
  EXPECT_THROW(sweepToAccuracy({scene("coulomb-oscillator.toml")}, 1.5, 5, 320, *solver, tightOptions(),
                               grid(0.5, 0.6, 0.05), false),
               InputError);
  EXPECT_THROW(sweepToAccuracy({scene("coulomb-oscillator.toml")}, 1e-3, 5, 320, *solver, tightOptions(),
                               grid(0.5, 0.6, -0.05), false),
               InputError);
}

}  // namespace
}  // namespace eqhb
