// Law invariants are measured against scales that do not vanish: a wall
// that is never touched (pressure ≡ 0 up to solver noise) or a friction
// contact that never slips (velocity ≡ 0 up to rounding) must not read as a
// law broken to 100%, while a real violation still reads as one, in any units.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "eqhb/backends/registry.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/harmonic_balance/invariants.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

using Measures = std::map<std::string, double>;

Measures asMap(const std::vector<std::pair<std::string, double>>& v) { return Measures(v.begin(), v.end()); }

// One period of a contact that stays open (|x| ≤ unit, the wall at 2 unit)
// with a pressure of the given amplitude that changes sign.
LawSamples openContact(double unit, double pressure_amplitude) {
  const int n = 256;
  LawSamples s;
  s.resize(n, 1);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    s.displacement(i, 0) = unit * std::cos(t);
    s.velocity(i, 0) = -unit * std::sin(t);
    s.force(i, 0) = pressure_amplitude * std::sin(3 * t);
    s.force_rate(i, 0) = 3 * pressure_amplitude * std::cos(3 * t);
  }
  return s;
}

TEST(InvariantScales, AnOpenContactWithPressureNoiseIsNotAPullingWall) {
  const Signorini wall(2.0, SignoriniForm::kMin);
  PhysicalScales scales;  // F = X = V = 1: the problem's own units
  const Measures m = asMap(wall.violations(openContact(1.0, 1e-13), scales));
  // Against max|p| = 1e-13 the noise reads negative_pressure = 1.
  EXPECT_LT(m.at("negative_pressure"), 1e-9);
  EXPECT_LT(m.at("complementarity"), 1e-9);
  EXPECT_EQ(m.at("penetration"), 0.0);
}

TEST(InvariantScales, APullingWallStillReadsAsOneInAnyUnits) {
  for (double unit : {1e-11, 1.0, 1e6}) {
    PhysicalScales scales;
    scales.force = scales.displacement = scales.velocity = unit;
    // A pressure of the problem's size that changes sign: the wall pulls.
    const Measures m = asMap(Signorini(2.0 * unit, SignoriniForm::kMin).violations(openContact(unit, unit), scales));
    EXPECT_NEAR(m.at("negative_pressure"), 1.0, 1e-12) << "unit " << unit;
    // The same noise, in the same units, is still noise.
    const Measures quiet =
        asMap(Signorini(2.0 * unit, SignoriniForm::kMin).violations(openContact(unit, 1e-13 * unit), scales));
    EXPECT_LT(quiet.at("negative_pressure"), 1e-9) << "unit " << unit;
  }
}

TEST(InvariantScales, AWallNeverTouchedWithSolverNoiseInItsPressure) {
  // contact.toml with the wall at 3.5, beyond the free swing (3.2): p ≡ 0,
  // here with 1e-13 of noise on its first harmonic, as a solver leaves it
  // after a continuation through contact.
  const Scene scene = loadScene(test::problem("contact.toml"), {"law[0].gap=3.5"});
  auto system = makeHbSystem(scene.model, true);
  const SolverResult r = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
  ASSERT_TRUE(r.converged()) << r.summary();
  Eigen::VectorXd full = system->fullCoefficients(r.solution);
  const int nb = scene.model.basis.size(), first_harmonic = scene.model.basis.offset(1);
  full[scene.model.structure.dofs() * nb + first_harmonic] += 1e-13;
  const auto reports = checkInvariants(scene.model, full);
  ASSERT_EQ(reports.size(), 1u);
  const Measures m = asMap(reports[0].violations);
  // Against max|p| = 1e-13 that noise read as a pulling wall: 1.
  EXPECT_LT(m.at("negative_pressure"), 1e-9);
  EXPECT_LT(m.at("complementarity"), 1e-9);
}

TEST(InvariantScales, AStuckFrictionContactDoesNotSlipOnRoundingNoise) {
  // friction-1d with μN = 100 above the load 20: DOF 2 never moves, the
  // friction force carries the spring (|r| ≈ 10.9 < μN).
  const Scene scene = loadScene(test::problem("friction-1d.toml"), {"law[0].muN=100"});
  auto system = makeHbSystem(scene.model, true);
  const SolverResult r = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
  ASSERT_TRUE(r.converged()) << r.summary();
  const auto reports = checkInvariants(scene.model, system->fullCoefficients(r.solution));
  ASSERT_EQ(reports.size(), 1u);
  const Measures m = asMap(reports[0].violations);
  // Against max|v| ≈ 1e-14 every sample counted as sliding: 1.10.
  EXPECT_LT(m.at("sliding_force_error"), 1e-6);
  EXPECT_LT(m.at("force_limit_excess"), 1e-6);
}

TEST(InvariantScales, ASlippingContactStillShowsAWrongForce) {
  // Coulomb samples sliding at the problem's velocity with the force of the
  // wrong sign: sliding_force_error = |r + μN sign v| / μN = 2.
  const Coulomb1D friction(1.0, CoulombForm::kMinMax);
  const int n = 64;
  LawSamples s;
  s.resize(n, 1);
  for (int i = 0; i < n; ++i) {
    s.velocity(i, 0) = std::sin(2 * M_PI * (i + 0.5) / n);
    s.force(i, 0) = std::copysign(1.0, s.velocity(i, 0));
  }
  s.displacement.setZero();
  s.force_rate.setZero();
  const Measures m = asMap(friction.violations(s, PhysicalScales{}));
  EXPECT_NEAR(m.at("sliding_force_error"), 2.0, 1e-12);
}

}  // namespace
}  // namespace eqhb
