// The alternating frequency–time form of elastic dry friction (JenkinsAft):
// its Jacobian across samples against finite differences on both systems,
// a period that never slips against the linear structure, and harmonic
// balance on jenkins-1d against the exact orbit; the formulation key's
// errors and the setting that sets it on a whole scene.
#include <gtest/gtest.h>

#include "eqhb/app/scene_settings.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/joints/jenkins_aft.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/orbits/piecewise_linear_flow.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/scenes/scene.h"
#include "law_checks.h"
#include "test_support.h"

namespace eqhb {
namespace {

std::shared_ptr<Law> aft(double mu_n, double k_t) {
  return std::make_shared<JenkinsAft>(std::vector<JenkinsAft::Slider>{{mu_n, k_t}});
}

// How many samples stick, slip, and stick since a slip of the same period,
// at the law's last evaluation: the checks below must see all three.
struct Phases {
  int stick = 0, slip = 0, anchored = 0;
};
Phases phases(const Law& law, const Eigen::VectorXd& x) {
  LawSamples s;
  s.resize(static_cast<int>(x.size()), 1, law.historyTerms());
  s.displacement.col(0) = x;
  law.evaluate(s, true);
  Phases p;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (s.history_weight(i, 0) == 0.0) ++p.slip;
    else ++p.stick;
    if (s.history_weight(i, 0) != 0.0 && s.history_sample(i, 0) >= 0) ++p.anchored;
  }
  return p;
}

TEST(JenkinsAft, ReturnMapOnASine) {
  // x = sin θ, k_t = 2, μN = 1: the slider slips on the way up to the
  // maximum (F = −1 there, w = 1 − 1/2), then sticks, F = −2 (x − 1/2),
  // until F reaches +1 at x = 0, half a period later, and slips down.
  const int n = 400;
  LawSamples s;
  s.resize(n, 1, 1);
  for (int i = 0; i < n; ++i) s.displacement(i, 0) = std::sin(2 * M_PI * i / n);
  aft(1.0, 2.0)->evaluate(s, true);
  const Eigen::VectorXd force = -s.psi.col(0);  // λ = 0: Ψ = −F
  EXPECT_NEAR(force.maxCoeff(), 1.0, 1e-12);
  EXPECT_NEAR(force.minCoeff(), -1.0, 1e-12);
  for (int i = n / 4 + 1; i < n / 2; ++i) {
    EXPECT_NEAR(force[i], -2.0 * (s.displacement(i, 0) - 0.5), 1e-12) << i;
    EXPECT_EQ(s.history_sample(i, 0), n / 4) << i;  // stuck since the maximum
    EXPECT_EQ(s.history_weight(i, 0), -2.0) << i;
  }
  for (int i = 1; i < n / 4; ++i) EXPECT_EQ(s.history_weight(i, 0), 0.0) << i;  // slipping
  // Odd input, odd force (the periodic state does not depend on the start).
  for (int i = 1; i < n / 2; ++i) EXPECT_NEAR(force[i], -force[i + n / 2], 1e-12) << i;
}

TEST(JenkinsAft, AssembledJacobiansMatchFiniteDifferences) {
  // μN = 0.4, k_t = 1.5: on the random states of the check each period
  // sticks and slips (asserted below through the same z's displacement).
  for (unsigned seed : {3u, 7u, 11u}) {
    test::expectAssembledJacobiansMatch(aft(0.4, 1.5), "aft seed " + std::to_string(seed), seed);
    test::expectBetweenNodesMatches(aft(0.4, 1.5), "aft seed " + std::to_string(seed), seed);
  }
  Eigen::VectorXd x(64);
  for (int i = 0; i < 64; ++i) x[i] = 0.8 * std::cos(2 * M_PI * i / 64) + 0.3 * std::sin(6 * M_PI * i / 64);
  const Phases p = phases(*aft(0.4, 1.5), x);
  EXPECT_GT(p.stick, 5);
  EXPECT_GT(p.slip, 5);
  EXPECT_GT(p.anchored, 5);
}

// On an odd basis, larger N, the full system's sparse Jacobian equals its
// dense one and finite differences; the condensed one matches too.
TEST(JenkinsAft, SparseAndDenseJacobiansOnAnOddBasis) {
  HbModel model = loadScene(test::problem("jenkins-1d.toml"), {"law.formulation=\"aft\"",
                                                               "harmonic_balance.harmonics=5",
                                                               "harmonic_balance.samples=128"})
                      .model;
  for (bool condensed : {false, true}) {
    auto system = makeHbSystem(model, condensed);
    srand(5);
    const Eigen::VectorXd z = 6.0 * Eigen::VectorXd::Random(system->size());
    Eigen::VectorXd g(system->size());
    Eigen::MatrixXd j(system->size(), system->size());
    ASSERT_TRUE(system->residualAndJacobian(z, g, j));
    const Eigen::MatrixXd fd = test::finiteDifferenceJacobian(*system, z, 1e-6);
    EXPECT_LT((j - fd).cwiseAbs().maxCoeff(), 1e-5 * (1.0 + fd.cwiseAbs().maxCoeff())) << condensed;
    if (condensed) continue;
    SparseMatrix sparse = system->jacobianPattern();
    Eigen::VectorXd gs(system->size());
    ASSERT_TRUE(system->residualAndSparseJacobian(z, gs, sparse));
    EXPECT_EQ((Eigen::MatrixXd(sparse) - j).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ((gs - g).cwiseAbs().maxCoeff(), 0.0);
  }
}

// A period that never slips is linear: the structure with k_t added at the
// law's DOF (every harmonic of an odd basis), whatever N.
TEST(JenkinsAft, StuckOrbitIsTheLinearOne) {
  const double k_t = 5.0;
  for (int samples : {64, 200}) {
    HbModel model = loadScene(test::problem("jenkins-1d.toml"),
                              {"law.formulation=\"aft\"", "law.muN=1e6", "harmonic_balance.harmonics=5",
                               "harmonic_balance.samples=" + std::to_string(samples)})
                        .model;
    CondensedSystem system(model);
    // The law is affine in λ here: one Newton step from 0 solves it.
    Eigen::VectorXd g(system.size()), z = Eigen::VectorXd::Zero(system.size());
    Eigen::MatrixXd j(system.size(), system.size());
    ASSERT_TRUE(system.residualAndJacobian(z, g, j));
    z = -j.lu().solve(g);
    ASSERT_TRUE(system.residual(z, g));
    EXPECT_LT(g.cwiseAbs().maxCoeff(), 1e-10);
    const Eigen::VectorXd full = system.fullCoefficients(z);
    // The linear structure: K + k_t e₂e₂ᵀ, forced at harmonic 1 only.
    HbModel linear = model;
    linear.laws.clear();
    Eigen::MatrixXd stiffness(model.structure.stiffness);
    stiffness(1, 1) += k_t;
    linear.structure = LinearStructure::fromMassStiffnessDamping(Eigen::MatrixXd(model.structure.mass), stiffness,
                                                                 Eigen::MatrixXd(model.structure.damping));
    linear.structure.loads = model.structure.loads;
    FullSystem plain(linear);
    Eigen::VectorXd gl(plain.size()), zl = Eigen::VectorXd::Zero(plain.size());
    Eigen::MatrixXd jl(plain.size(), plain.size());
    ASSERT_TRUE(plain.residualAndJacobian(zl, gl, jl));
    zl = -jl.lu().solve(gl);
    const int nb = model.basis.size();
    EXPECT_LT((full.head(2 * nb) - zl).cwiseAbs().maxCoeff(), 1e-10 * zl.cwiseAbs().maxCoeff()) << samples;
    EXPECT_GT(zl.cwiseAbs().maxCoeff(), 1.0);
  }
}

// The sup error of harmonic balance against the exact orbit of jenkins-1d
// (closed-form flow, shot from the equality solution), over 256 instants,
// relative to max|x|.
double supError(const HbModel& model, const Eigen::VectorXd& full, const orbits::ShootingResult& orbit,
                const orbits::FlowSamples& samples) {
  double sup = 0.0;
  for (size_t s = 0; s < samples.times.size(); ++s)
    sup = std::max(sup, (orbits::harmonicState(model, full, samples.times[s]).head(2) -
                         samples.displacement.row(s).transpose())
                            .cwiseAbs()
                            .maxCoeff());
  return sup / orbit.max_abs.maxCoeff();
}

TEST(JenkinsAft, Jenkins1DAgainstTheExactOrbit) {
  const HbModel model = loadScene(test::problem("jenkins-1d.toml")).model;
  const orbits::PiecewiseLinearFlow flow(model, 0.0);
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  const double t0 = orbits::quietStartTime(model, hb);
  const auto orbit = shootPeriodicOrbit(flow, orbits::harmonicState(model, hb, t0), t0, orbits::ShootingOptions());
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  orbits::FlowSamples samples;
  for (int s = 0; s < 256; ++s) samples.times.push_back(t0 + flow.period() * s / 256);
  ASSERT_TRUE(flow.integrate(orbit.state, t0, flow.period(), false, &samples).ok);
  std::vector<double> errors;
  for (int h : {5, 10, 20}) {
    const HbModel m = loadScene(test::problem("jenkins-1d.toml"),
                                {"law.formulation=\"aft\"", "harmonic_balance.harmonics=" + std::to_string(h)})
                          .model;
    const auto solved = test::solveFromRest("jenkins-1d.toml", {"law.formulation=\"aft\"",
                                                                "harmonic_balance.harmonics=" + std::to_string(h)});
    ASSERT_TRUE(solved.result.converged()) << h << ": " << solved.result.summary();
    errors.push_back(supError(m, solved.full, orbit, samples));
  }
  // Measured 1.3e-3, 7.1e-4, ... (see the commit); the target is 0.2 % at H = 10.
  EXPECT_LT(errors[1], 2e-3);
  EXPECT_LT(errors[2], errors[0]);
  // The equality form at H = 10 is far off in comparison: AFT wins by > 3×.
  const auto equality = test::solveFromRest("jenkins-1d.toml");
  ASSERT_TRUE(equality.result.converged());
  EXPECT_LT(3.0 * errors[1], supError(model, equality.full, orbit, samples));
}

TEST(JenkinsAft, FormulationKeyErrorsNameTheField) {
  auto message = [](const std::vector<std::string>& set) {
    try {
      loadScene(test::problem("jenkins-1d.toml"), set);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({"law.formulation=\"fft\""}).find("law[0].formulation"), std::string::npos);
  EXPECT_NE(message({"law.formulation=\"fft\""}).find("\"equality\" or \"aft\""), std::string::npos);
  EXPECT_NE(message({"law.type=\"coulomb-1d\"", "law.formulation=\"aft\""}).find("law[0].formulation"),
            std::string::npos);
  EXPECT_EQ(message({"law.formulation=\"equality\""}), "");
  EXPECT_EQ(message({"law.formulation=\"aft\""}), "");
}

// The scene-wide setting (--formulation, Python's formulation=) sets every
// law that has the formulation and no other; a scene without one refuses it.
TEST(JenkinsAft, FormulationSettingSetsEveryLawThatHasIt) {
  app::SceneSettings settings;
  settings.path = test::problem("beam-damper-elastic.toml");
  settings.formulation = "aft";
  const Scene aft = app::loadScene(settings);
  ASSERT_EQ(aft.model.laws.size(), 5u);
  for (const AttachedLaw& a : aft.model.laws) EXPECT_NE(dynamic_cast<const JenkinsAft*>(a.law.get()), nullptr);
  // Back to the equality form over a scene that sets aft.
  settings.formulation = "equality";
  settings.overrides = {"law[2].formulation=\"aft\""};
  for (const AttachedLaw& a : app::loadScene(settings).model.laws)
    EXPECT_EQ(dynamic_cast<const JenkinsAft*>(a.law.get()), nullptr);
  // A scene mixing laws: the one without an AFT form keeps its equality form.
  settings.path = test::problem("jenkins-1d.toml");
  settings.overrides = {};
  settings.formulation = "aft";
  EXPECT_NE(dynamic_cast<const JenkinsAft*>(app::loadScene(settings).model.laws[0].law.get()), nullptr);
  auto message = [&](const std::string& scene, const std::string& formulation) {
    settings.path = test::problem(scene);
    settings.formulation = formulation;
    try {
      app::loadScene(settings);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string none = message("friction-1d.toml", "aft");
  EXPECT_EQ(none.rfind("formulation = aft", 0), 0u) << none;
  EXPECT_NE(none.find("laws with it: jenkins"), std::string::npos) << none;
  EXPECT_EQ(message("friction-1d.toml", "equality"), "");
  EXPECT_NE(message("jenkins-1d.toml", "fft").find("must be equality or aft"), std::string::npos);
}

// A 1-DOF jenkins law takes the AFT form unless the scene asks for the
// equality form, by name or by one of its keys (form, rho, rho_factor, as
// --form and --rho set them); on 2 DOFs it has only the equality form. The
// accuracy target's ρ candidates then leave it alone.
TEST(JenkinsAft, OneDofJenkinsDefaultsToAftUnlessTheEqualityFormIsAskedFor) {
  const std::string field = test::problem("field/tmdsimpy-sdof-jenkins-f33.toml");  // muN and k_t only
  auto aft = [&](const std::vector<std::string>& set) { return inAftForm(*loadScene(field, set).model.laws[0].law); };
  EXPECT_TRUE(aft({}));
  EXPECT_FALSE(aft({"law[0].formulation=\"equality\""}));
  EXPECT_FALSE(aft({"law[0].rho=0.5"}));
  EXPECT_FALSE(aft({"law[0].rho_factor=0.1"}));
  EXPECT_FALSE(aft({"law[0].form=\"projection\""}));
  EXPECT_TRUE(aft({"law[0].rho=0.5", "law[0].formulation=\"aft\""}));
  // Shipped scenes that name form and rho keep their equality form.
  EXPECT_FALSE(inAftForm(*loadScene(test::problem("jenkins-1d.toml")).model.laws[0].law));
  app::SceneSettings settings;
  settings.path = field;
  EXPECT_FALSE(app::documentRhos(settings, {})[0].has_value());
  settings.rho = 0.5;  // --rho asks for the equality form's ρ
  EXPECT_FALSE(inAftForm(*app::loadScene(settings).model.laws[0].law));
}

}  // namespace
}  // namespace eqhb
