// One problem in several systems of units is one problem: NLvib's cantilever
// with dry friction (cantilever_units.h) on its exact Coulomb law converges
// in the same iterations to the same answer in each, and its sweep converges
// at every point in each.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eqhb/app/sweep.h"
#include "eqhb/stability/hill_stability.h"
#include "cantilever_units.h"
#include "test_support.h"

namespace eqhb {
namespace {

using test::Units;
using test::unitSystems;

test::UnitsOutcome solveIn(const Units& u) { return test::solveCantileverIn(u, 256.0); }

TEST(UnitSystems, OneSolveInEveryUnitSystem) {
  const test::UnitsOutcome si = solveIn(unitSystems()[0]);
  ASSERT_TRUE(si.result.converged()) << si.result.summary();
  for (const Units& u : unitSystems()) {
    const test::UnitsOutcome o = solveIn(u);
    ASSERT_TRUE(o.result.converged()) << u.name << ": " << o.result.summary();
    // Where the units are powers of two the solve is the same bit for bit;
    // elsewhere round-off may change a step or two of the path.
    if (u.binary) EXPECT_EQ(o.result.iterations, si.result.iterations) << u.name;
    EXPECT_NEAR(o.result.iterations, si.result.iterations, 2) << u.name;
    EXPECT_NEAR(o.contact, si.contact, 1e-8 * si.contact) << u.name;
  }
}

TEST(UnitSystems, EveryPointOfTheSweepInEveryUnitSystem) {
  for (const Units& u : unitSystems()) {
    app::SceneSettings scene;
    scene.path = test::problem("cantilever-friction-si.toml");
    scene.overrides = test::cantileverInUnits(u, 256.0);
    const app::SweepResult result = app::sweep(scene, app::SweepOptions{});
    EXPECT_EQ(result.curve.failed_points, 0) << u.name;
    EXPECT_EQ(result.curve.points.size(), 101u) << u.name;
  }
}

// Hill's method gives one verdict and one spectral radius (a dimensionless
// number) in every system of units: in SI the beam's stiffness rows (1e8)
// against the law's (1) made every shift's pencil look singular, and no
// verdict came out.
TEST(UnitSystems, HillStabilityInEveryUnitSystem) {
  double radius_si = 0.0;
  for (const Units& u : unitSystems()) {
    const Scene scene =
        loadScene(test::problem("cantilever-friction-si.toml"), test::cantileverInUnits(u, 256.0));
    auto system = makeHbSystem(scene.model, true);
    SolverOptions options;
    options.residual_tolerance = 1e-10;
    const SolverResult solved = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), options);
    ASSERT_TRUE(solved.converged()) << u.name;
    HbModel model = scene.model;
    const HillResult r = hillStability(model, system->fullCoefficients(solved.solution));
    ASSERT_TRUE(r.failure.empty()) << u.name << ": " << r.failure;
    EXPECT_TRUE(r.stable) << u.name;
    if (radius_si == 0.0) radius_si = r.spectral_radius;
    EXPECT_NEAR(r.spectral_radius, radius_si, 1e-6) << u.name;
  }
}

}  // namespace
}  // namespace eqhb
