// One problem in several systems of units is one problem: NLvib's cantilever
// with dry friction (problems/cantilever-friction-si.toml, SI) posed in
// mm/N/ms, with a time unit of 1/128 s (every conversion exact in binary)
// and nondimensional (length 2 m, the free first mode's 1/ω as time, the
// friction limit 1.5 N as force) converges in the same iterations to the
// same answer, and its sweep converges at every point in each.
#include <gtest/gtest.h>

#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "eqhb/app/sweep.h"
#include "eqhb/backends/registry.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

// A unit system: its length, time and force units in metres, seconds and newtons.
struct Units {
  const char* name;
  double length, time, force;
};

const std::vector<Units>& unitSystems() {
  static const std::vector<Units> all = {{"SI", 1.0, 1.0, 1.0},
                                         {"mm/N/ms", 1e-3, 1e-3, 1.0},
                                         {"time unit 1/128 s", 1.0, 1.0 / 128.0, 1.0},
                                         {"nondimensional", 2.0, 1.0 / 123.34, 1.5}};
  return all;
}

// Every digit of `value` (a TOML number).
std::string exact(double value) {
  std::ostringstream out;
  out << std::setprecision(17) << value;
  return out.str();
}

// The scene's parameters (SI) in `u`, as --set overrides.
std::vector<std::string> inUnits(const Units& u) {
  const double x = u.length, t = u.time, f = u.force;
  const double mass = f * t * t / x;  // the unit of mass, in kg
  std::vector<std::string> set;
  auto put = [&](const std::string& key, double value) { set.push_back(key + "=" + exact(value)); };
  put("structure.E", 185e9 * x * x / f);
  put("structure.I", 2.5e-5 / (x * x * x * x));
  put("structure.rhoA", 234.9 * x / mass);
  put("structure.L", 2.0 / x);
  set.push_back("structure.rayleigh=[0.0, " + exact(8.033e-5 / t) + "]");
  put("forcing[0].cos", 0.2 / f);
  put("law[0].muN", 1.5 / f);
  put("harmonic_balance.omega", 256.0 * t);
  put("sweep.from", 370.0 * t);
  put("sweep.to", 110.0 * t);
  return set;
}

struct Outcome {
  SolverResult result;
  double contact = 0.0;  // max|x| at the contact's DOF, in metres
};

Outcome solveIn(const Units& u) {
  const Scene scene = loadScene(test::problem("cantilever-friction-si.toml"), inUnits(u));
  auto system = makeHbSystem(scene.model, true);
  Outcome o;
  o.result = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
  const int dof = scene.model.laws[0].attachment.dof(0);
  o.contact =
      summarize(scene.model, system->fullCoefficients(o.result.solution)).displacements[dof].max_abs * u.length;
  return o;
}

TEST(UnitSystems, OneSolveInEveryUnitSystem) {
  const Outcome si = solveIn(unitSystems()[0]);
  ASSERT_TRUE(si.result.converged()) << si.result.summary();
  for (const Units& u : unitSystems()) {
    const Outcome o = solveIn(u);
    ASSERT_TRUE(o.result.converged()) << u.name << ": " << o.result.summary();
    EXPECT_EQ(o.result.iterations, si.result.iterations) << u.name;
    EXPECT_NEAR(o.contact, si.contact, 1e-8 * si.contact) << u.name;
  }
}

TEST(UnitSystems, EveryPointOfTheSweepInEveryUnitSystem) {
  for (const Units& u : unitSystems()) {
    app::SceneSettings scene;
    scene.path = test::problem("cantilever-friction-si.toml");
    scene.overrides = inUnits(u);
    const app::SweepResult result = app::sweep(scene, app::SweepOptions{});
    EXPECT_EQ(result.curve.failed_points, 0) << u.name;
    EXPECT_EQ(result.curve.points.size(), 101u) << u.name;
  }
}

}  // namespace
}  // namespace eqhb
