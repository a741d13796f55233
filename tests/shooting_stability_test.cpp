#include "eqhb/stability/shooting_stability.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/stability/curve_stability.h"
#include "eqhb/stability/monodromy_stability.h"
#include "test_support.h"

namespace eqhb {
namespace {

HbModel modelAt(const std::string& file, double omega, int harmonics) {
  HbModel model = loadScene(test::problem(file), {"harmonic_balance.omega=" + std::to_string(omega)}).model;
  model.basis = HarmonicSet(model.basis.kind(), harmonics);
  model.samples = std::max(model.samples, samplesForHarmonics(model, harmonics));
  return model;
}

struct Shot {
  HillResult result;
  double distance = 0.0;
};

Shot shoot(const std::string& file, double omega, int harmonics) {
  const HbModel model = modelAt(file, omega, harmonics);
  ShootingStability shooting(model);
  Shot s;
  s.result = shooting.analyse(omega, test::harmonicBalance(model));
  s.distance = shooting.lastDistance();
  const orbits::ShootingResult& shot = shooting.lastShooting();
  std::printf("  H=%d: %d Newton steps, %d period maps, %.2f ms a map with Jacobian, %.2f ms in all\n", harmonics,
              shot.iterations, shot.flow_evaluations, 1e3 * shot.seconds_per_orbit, 1e3 * s.result.seconds);
  return s;
}

// The exact multipliers do not depend on the harmonic-balance solution the
// orbit is shot from: at H = 20 the radius equals the one shot from the
// H = 5 and H = 40 solutions (different starts, one orbit) within 1e-3,
// where the monodromy over the H = 20 samples is 0.009 and 0.018 off on
// friction-1d's stick–slip orbits (0.308, 0.4). A method that carried the
// series' truncation error (the monodromy's radius moves by more than 1e-3
// between H = 5 and 40 at every case here) fails this.
TEST(ShootingStability, RadiusDoesNotDependOnH) {
  const std::pair<const char*, double> cases[] = {
      {"friction-1d.toml", 0.308}, {"friction-1d.toml", 0.4}, {"friction-1d.toml", 0.55}, {"coulomb-oscillator.toml", 0.6}};
  for (const auto& [file, omega] : cases) {
    const Shot at5 = shoot(file, omega, 5), at20 = shoot(file, omega, 20), at40 = shoot(file, omega, 40);
    std::printf("%s w=%.3f: radius %.8f (H=5, distance %.2g), %.8f (H=20, %.2g), %.8f (H=40, %.2g), %.2f ms\n", file,
                omega, at5.result.spectral_radius, at5.distance, at20.result.spectral_radius, at20.distance,
                at40.result.spectral_radius, at40.distance, 1e3 * at20.result.seconds);
    for (const Shot* s : {&at5, &at20, &at40}) {
      EXPECT_EQ(s->result.method, "shooting") << file << " " << omega << ": " << s->result.note;
      EXPECT_TRUE(s->result.note.empty()) << s->result.note;
      EXPECT_LE(s->distance, ShootingStability::kSameOrbitDistance);
    }
    EXPECT_NEAR(at20.result.spectral_radius, at5.result.spectral_radius, 1e-3) << file << " " << omega;
    EXPECT_NEAR(at20.result.spectral_radius, at40.result.spectral_radius, 1e-3) << file << " " << omega;
    EXPECT_EQ(at20.result.stable, at40.result.stable);
    // One multiplier per state [x; v].
    EXPECT_EQ(static_cast<int>(at20.result.exponents.size()), 2 * modelAt(file, omega, 5).structure.dofs());
    // On the stick–slip orbits the monodromy over the samples depends on H
    // (the reference above would catch a shooting that returned it); where
    // friction only reverses (0.55) it is within 1e-4 already.
    if (std::string(file) != "friction-1d.toml" || omega > 0.5) continue;
    const HbModel low = modelAt(file, omega, 5), high = modelAt(file, omega, 40);
    const double m5 = MonodromyStability(low).analyse(omega, test::harmonicBalance(low)).spectral_radius;
    const double m40 = MonodromyStability(high).analyse(omega, test::harmonicBalance(high)).spectral_radius;
    std::printf("  monodromy %.6f (H=5), %.6f (H=40)\n", m5, m40);
    EXPECT_GT(std::abs(m5 - m40), 1e-3) << file << " " << omega;
  }
}

// A start that is not the orbit's series (the H = 20 solution at half its
// amplitude): shooting reaches the one orbit of this forcing, far from the
// given series, so the point is answered by the monodromy and says why.
TEST(ShootingStability, AnotherOrbitFallsBackToTheMonodromy) {
  const HbModel model = modelAt("friction-1d.toml", 0.4, 20);
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  ShootingStability shooting(model);
  const HillResult right = shooting.analyse(0.4, hb);
  EXPECT_EQ(right.method, "shooting");
  const HillResult wrong = shooting.analyse(0.4, 0.5 * hb);
  EXPECT_EQ(wrong.method, "monodromy");
  EXPECT_NE(wrong.note.find("another orbit"), std::string::npos) << wrong.note;
  EXPECT_GT(shooting.lastDistance(), ShootingStability::kSameOrbitDistance);
  EXPECT_TRUE(shooting.lastShooting().converged);
}

// Unstable orbits too: along the arclength curve of the penalty wall
// (problems/penalty-contact.toml, 0.3-0.9, H = 20) every third point is shot;
// where shooting answers itself, the monodromy over the series (another
// computation: the linearised dynamics over the harmonic-balance samples)
// gives the same verdict, and Hill's does too away from the unit circle
// (|radius − 1| > 0.01: at 0.798 Hill finds 0.9987 where shooting finds
// 1.0016). The curve has unstable stretches (0.435-0.46, 0.53, 0.67-0.78):
// a method that called every orbit stable fails.
TEST(ShootingStability, VerdictsOnThePenaltyWallCurveIncludingUnstableOrbits) {
  const HbModel model = loadScene(test::problem("penalty-contact.toml")).model;
  ContinuationOptions range;
  range.from = 0.3;
  range.to = 0.9;
  auto solver = makeSolver("dogleg");
  const Curve curve = sweepArclength(model, *solver, SolverOptions(), range);
  ASSERT_GT(curve.points.size(), 100u) << curve.stop_reason;
  ShootingStability shooting(model);
  MonodromyStability monodromy(model);
  HillStability hill(model);
  int shot = 0, unstable = 0, stable = 0, hill_checked = 0;
  for (size_t i = 0; i < curve.points.size(); i += 3) {
    const CurvePoint& p = curve.points[i];
    if (!p.converged) continue;
    const HillResult s = shooting.analyse(p.omega, p.full);
    if (s.method != "shooting") continue;
    ++shot;
    const HillResult m = monodromy.analyse(p.omega, p.full);
    EXPECT_EQ(m.stable, s.stable) << "omega " << p.omega << ": monodromy " << m.spectral_radius << ", shooting "
                                  << s.spectral_radius;
    (s.stable ? stable : unstable) += 1;
    if (i % 9 == 0 && std::abs(s.spectral_radius - 1.0) > 0.01) {
      const HillResult h = hill.analyse(p.omega, p.full);
      EXPECT_EQ(h.stable, s.stable) << "omega " << p.omega << ": Hill " << h.spectral_radius << ", shooting "
                                    << s.spectral_radius;
      ++hill_checked;
    }
  }
  std::printf("penalty wall: %d points shot, %d unstable, %d stable, %d checked against Hill\n", shot, unstable, stable,
              hill_checked);
  EXPECT_GE(shot, 100);
  EXPECT_GE(unstable, 30);
  EXPECT_GE(stable, 30);
}

// "shooting" by name through analyseStability; laws without an exact flow
// are refused naming the field; the names are listed by the validation.
TEST(ShootingStability, MethodChoice) {
  const HbModel friction = loadScene(test::problem("friction-1d.toml")).model;
  const Eigen::VectorXd hb = test::harmonicBalance(friction);
  HillOptions options;
  options.method = "shooting";
  EXPECT_EQ(analyseStability(friction, hb, options).method, "shooting");
  EXPECT_TRUE(ShootingStability::supports(friction));
  const HbModel lap = loadScene(test::problem("lap-joint.toml")).model;
  EXPECT_FALSE(ShootingStability::supports(lap));
  EXPECT_THROW(ShootingStability{lap}, InputError);
  options.method = "floquet";
  const std::string message = test::messageOf([&] { options.validate(); });
  EXPECT_NE(message.find("shooting"), std::string::npos) << message;
  EXPECT_NE(message.find("stability_method"), std::string::npos) << message;
}

}  // namespace
}  // namespace eqhb
