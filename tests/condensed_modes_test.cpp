// The nonlinear mode on the condensed system (condensed_mode_system.h): its
// Jacobian against finite differences (ω and ξ columns through A_k(ω, ξ)⁻¹),
// its equations against the full mode system's at the recovered motion,
// and backbones equal to the full system's on the shipped friction scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "eqhb/app/modes.h"
#include "eqhb/error.h"
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/laws/joints/jenkins.h"
#include "eqhb/modes/backbone.h"
#include "eqhb/modes/condensed_mode_system.h"
#include "eqhb/modes/full_mode_system.h"
#include "eqhb/modes/mode_path_system.h"
#include "test_support.h"

namespace eqhb {
namespace {

// A 3-DOF chain with non-proportional damping, a cubic
// spring on DOF 2 and a Jenkins element on DOF 3, a constant load, and every
// harmonic up to 3 (harmonic 0 included).
HbModel chain() {
  Eigen::MatrixXd m(3, 3), k(3, 3), c(3, 3);
  m << 1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.5;
  k << 3.0, -1.0, 0.0, -1.0, 2.5, -1.5, 0.0, -1.5, 2.0;
  c << 0.05, 0.01, 0.0, 0.01, 0.02, 0.0, 0.0, 0.0, 0.04;
  HbModel model;
  model.structure = LinearStructure::fromMassStiffnessDamping(m, k, c);
  model.structure.loads.push_back({0, 0, 0.3, 0.0});
  model.laws.push_back({{1}, std::make_shared<CubicStiffness>(0.7)});
  model.laws.push_back({{2}, std::make_shared<Jenkins>(1, 1.0, 0.4, FrictionForm::kProjection, RhoSetting(0.7))});
  model.basis = HarmonicSet(HarmonicKind::kAll, 3);
  model.samples = 64;
  return model;
}

Eigen::VectorXd somePoint(const ModeSystem& system) {
  Eigen::VectorXd z = Eigen::VectorXd::LinSpaced(system.size(), -0.3, 0.5);
  z[system.omegaIndex()] = 1.1;
  z[system.xiIndex()] = 0.07;
  return z;
}

TEST(CondensedModeSystem, JacobianMatchesFiniteDifferencesInEveryColumn) {
  const HbModel model = chain();
  CondensedModeSystem system(model, linearModes(model)[0].shape, true);
  system.setAmplitude(0.4);
  const Eigen::VectorXd z = somePoint(system);
  Eigen::VectorXd g(system.size());
  Eigen::MatrixXd j(system.size(), system.size());
  ASSERT_TRUE(system.residualAndJacobian(z, g, j));
  const Eigen::MatrixXd fd = test::finiteDifferenceJacobian(system, z, 1e-7);
  EXPECT_LT((j - fd).cwiseAbs().maxCoeff(), 1e-6 * std::max(1.0, fd.cwiseAbs().maxCoeff()));
  EXPECT_GT(j.col(system.omegaIndex()).norm(), 0.1);  // the columns checked are not empty
  EXPECT_GT(j.col(system.xiIndex()).norm(), 1e-3);
  // The residual alone is the one the Jacobian came with.
  Eigen::VectorXd g_alone(system.size());
  ASSERT_TRUE(system.residual(z, g_alone));
  EXPECT_LT((g - g_alone).cwiseAbs().maxCoeff(), 1e-14 * std::max(1.0, g.norm()));
}

TEST(CondensedModeSystem, EquationsAreTheFullSystemsAtTheRecoveredMotion) {
  // x̂ recovered from λ̂ (the fundamental bordered by φᵀ M X₁ = a) meets the
  // full system's amplitude and phase rows and its dynamics rows but for
  // the fundamental's defect −μ M φ (cos rows −Re μ M φ, sin rows Im μ M φ,
  // μ the condensed system's last two rows); the law rows are the same.
  const HbModel model = chain();
  const Eigen::VectorXd shape = linearModes(model)[0].shape;
  CondensedModeSystem condensed(model, shape, true);
  FullModeSystem full(model, shape, true);
  condensed.setAmplitude(0.4);
  full.setAmplitude(0.4);
  const Eigen::VectorXd z = somePoint(condensed);
  Eigen::VectorXd point(full.size());
  point << condensed.fullCoefficients(z), z.tail(2);
  EXPECT_LT((condensed.fromFullPoint(point) - z).cwiseAbs().maxCoeff(), 1e-15);
  Eigen::VectorXd g_condensed(condensed.size()), g_full(full.size());
  ASSERT_TRUE(condensed.residual(z, g_condensed));
  ASSERT_TRUE(full.residual(point, g_full));
  const int n = 3, nb = model.basis.size(), laws = condensed.coefficientCount();
  const double tolerance = 1e-12 * std::max(1.0, point.cwiseAbs().maxCoeff());
  const Eigen::VectorXd mass_shape = Eigen::MatrixXd(model.structure.mass) * shape;
  const double mu_re = g_condensed[laws], mu_im = g_condensed[laws + 1];
  EXPECT_GT(std::hypot(mu_re, mu_im), 1e-3);  // a point off the mode: the defect checked is not zero
  const int fundamental = model.basis.offset(1);  // kAll: harmonics 0, 1, 2, 3
  for (int i = 0; i < n; ++i)
    for (int o = 0; o < nb; ++o) {
      double expected = 0.0;
      if (o == fundamental) expected = -mu_re * mass_shape[i];
      if (o == fundamental + 1) expected = mu_im * mass_shape[i];
      EXPECT_NEAR(g_full[i * nb + o], expected, tolerance) << "DOF " << i << " coefficient " << o;
    }
  EXPECT_LT((g_full.segment(n * nb, laws) - g_condensed.head(laws)).cwiseAbs().maxCoeff(),
            1e-12 * std::max(1.0, g_condensed.norm()));
  EXPECT_LT(g_full.tail(2).cwiseAbs().maxCoeff(), tolerance);  // φᵀ M x̂₁ = a exactly
  EXPECT_GT(g_condensed.head(laws).norm(), 0.1);  // the law rows compared are not zero
}

TEST(CondensedModeSystem, PathSystemJacobianMatchesFiniteDifferences) {
  const HbModel model = chain();
  CondensedModeSystem mode(model, linearModes(model)[0].shape, true);
  ModePathSystem path(mode);
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(path.size(), -0.3, 0.5);
  y[mode.omegaIndex()] = 1.1;
  y[mode.xiIndex()] = 0.07;
  y[path.sIndex()] = std::log(0.4);
  const PathWeights weights = PathWeights::at(mode, y, 0.05, 0.2);
  path.setConstraint(weights, Eigen::VectorXd::LinSpaced(path.size(), 1.0, 2.0), y * 1.01);
  Eigen::VectorXd g(path.size());
  Eigen::MatrixXd j(path.size(), path.size());
  ASSERT_TRUE(path.residualAndJacobian(y, g, j));
  const Eigen::MatrixXd fd = test::finiteDifferenceJacobian(path, y, 1e-7);
  EXPECT_LT((j - fd).cwiseAbs().maxCoeff(), 1e-6 * std::max(1.0, fd.cwiseAbs().maxCoeff()));
}

TEST(CondensedModeSystem, RefusesAStructureWithoutLawsAndASingularStiffness) {
  HbModel linear = chain();
  linear.laws.clear();
  EXPECT_THROW(CondensedModeSystem(linear, linearModes(linear)[0].shape), InputError);
  HbModel free = chain();
  free.structure = LinearStructure::fromMassStiffnessDamping(
      Eigen::MatrixXd(free.structure.mass), Eigen::MatrixXd::Zero(3, 3), Eigen::MatrixXd(free.structure.damping));
  free.structure.loads.clear();
  Eigen::VectorXd shape = Eigen::VectorXd::Zero(3);
  shape[0] = 1.0;
  try {
    CondensedModeSystem system(free, shape);
    FAIL() << "a singular K was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stiffness"), std::string::npos) << e.what();
  }
}

// The backbone of a shipped scene on both systems: the same modes. The
// full system's default tolerance is on forces of the size of K x, which
// leaves ζ near resonance looser than the condensed system's (beam-damper:
// 1.8e-4 relative at a = 6.7); `full_tolerance` tightens it.
void expectSameBackbone(const std::string& scene, int mode, double full_tolerance = 1e-10,
                        double relative = 1e-7) {
  app::SceneSettings settings;
  settings.path = test::problem(scene);
  app::ModesOptions o;
  o.mode = mode;
  o.condensed = true;
  const app::ModesRun condensed = app::modes(settings, o);
  o.condensed = false;
  o.solver_options.residual_tolerance = full_tolerance;
  const app::ModesRun full = app::modes(settings, o);
  EXPECT_FALSE(full.backbone.condensed);
  EXPECT_TRUE(condensed.backbone.condensed);
  ASSERT_TRUE(full.backbone.complete()) << scene;
  ASSERT_TRUE(condensed.backbone.complete()) << scene;
  ASSERT_EQ(full.backbone.points.size(), condensed.backbone.points.size()) << scene;
  for (size_t i = 0; i < full.backbone.points.size(); ++i) {
    const BackbonePoint &f = full.backbone.points[i], &c = condensed.backbone.points[i];
    EXPECT_EQ(f.amplitude, c.amplitude);
    EXPECT_NEAR(c.omega, f.omega, 0.1 * relative * f.omega) << scene << " point " << i;
    EXPECT_NEAR(c.damping_ratio, f.damping_ratio, relative * std::max(f.damping_ratio, 1e-3)) << scene << " point " << i;
    EXPECT_LT((c.full - f.full).cwiseAbs().maxCoeff(), relative * f.full.cwiseAbs().maxCoeff()) << scene << " point " << i;
  }
}

TEST(CondensedModeSystem, BackbonesEqualTheFullSystemsOnTheFrictionScenes) {
  expectSameBackbone("friction-1d.toml", 1);
  expectSameBackbone("jenkins-1d.toml", 1);
  expectSameBackbone("contact.toml", 1);
  expectSameBackbone("penalty-contact.toml", 1);
}

TEST(CondensedModeSystem, BeamDamperSlidingModeMatchesTheTightFullSolve) {
  // 120 DOFs, five Coulomb dampers: the sliding mode resonates all along,
  // where an unbordered A₁⁻¹ lost every point (not_progressing). Between
  // a = 45 and 58 the truncated system has roots 6e-5 apart in ζ, which
  // solves from other starts reach (the full one at 1e-10 and 1e-13 too).
  expectSameBackbone("beam-damper.toml", 1, 1e-13, 1e-4);
}

TEST(CondensedModeSystem, PreloadedDamperHeldModeMatchesTheFullSystems) {
  // About the static state of a preloaded contact, from the held blade
  // (1389.52) to the free one (656.3).
  expectSameBackbone("blade-tip-damper.toml", 1, 1e-12, 1e-5);
}

}  // namespace
}  // namespace eqhb
