// One problem in several systems of units is one problem: NLvib's cantilever
// with dry friction (cantilever_units.h) on its exact Coulomb law converges
// in the same iterations to the same answer in each, and its sweep converges
// at every point in each.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eqhb/app/sweep.h"
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

}  // namespace
}  // namespace eqhb
