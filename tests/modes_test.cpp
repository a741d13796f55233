// Nonlinear modes (lib/eqhb/modes): the mode system's Jacobian against finite
// differences, and backbones against what is known in closed form: a linear
// structure's modal frequency and damping ratio, a Jenkins element's
// describing function and dissipated energy, Duffing's backbone at small
// amplitude, and exact Coulomb between its stuck and free limits.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "eqhb/app/modes.h"
#include "eqhb/error.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/laws/joints/jenkins.h"
#include "eqhb/laws/law_attachment.h"
#include "eqhb/modes/backbone.h"
#include "eqhb/modes/mode_path_system.h"
#include "eqhb/modes/full_mode_system.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

HbModel oneDof(double m, double c, double k, HarmonicKind kind, int harmonics, int samples) {
  HbModel model;
  model.structure = LinearStructure::fromMassStiffnessDamping(
      Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, k), Eigen::MatrixXd::Constant(1, 1, c));
  model.basis = HarmonicSet(kind, harmonics);
  model.samples = samples;
  return model;
}

// The 2-DOF chain with Rayleigh damping C = α M + β K (modes decouple).
HbModel rayleighChain(double alpha, double beta) {
  Eigen::MatrixXd m(2, 2), k(2, 2);
  m << 1.0, 0.0, 0.0, 2.0;
  k << 3.0, -1.0, -1.0, 1.0;
  HbModel model;
  model.structure = LinearStructure::fromMassStiffnessDamping(m, k, alpha * m + beta * k);
  model.basis = HarmonicSet(HarmonicKind::kOdd, 3);
  model.samples = 32;
  return model;
}

Backbone backboneOf(const HbModel& model, int mode, double from, double to, int points,
                    const SolverOptions& solver_options = SolverOptions()) {
  auto solver = makeSolver("dogleg");
  BackboneOptions o;
  o.mode = mode;
  o.from = from;
  o.to = to;
  o.points = points;
  return followBackbone(model, *solver, solver_options, o);
}

TEST(ModeSystem, JacobianMatchesFiniteDifferencesInEveryColumn) {
  // A smooth law (cubic) on a chain with non-proportional damping, at a
  // state with every harmonic, ω and ξ away from any special value.
  HbModel model = rayleighChain(0.03, 0.01);
  model.structure = LinearStructure::fromMassStiffnessDamping(
      Eigen::MatrixXd(model.structure.mass), Eigen::MatrixXd(model.structure.stiffness),
      Eigen::MatrixXd(model.structure.damping) + Eigen::MatrixXd::Identity(2, 2) * 0.02);
  model.laws.push_back({{1}, std::make_shared<CubicStiffness>(0.7)});
  model.basis = HarmonicSet(HarmonicKind::kAll, 3);
  model.samples = 32;
  const std::vector<LinearMode> modes = linearModes(model);
  FullModeSystem system(model, modes[0].shape);
  system.setAmplitude(0.4);
  Eigen::VectorXd z = Eigen::VectorXd::LinSpaced(system.size(), -0.3, 0.5);
  z[system.omegaIndex()] = 0.9;
  z[system.xiIndex()] = 0.05;
  Eigen::VectorXd g(system.size());
  Eigen::MatrixXd j(system.size(), system.size());
  ASSERT_TRUE(system.residualAndJacobian(z, g, j));
  const Eigen::MatrixXd fd = test::finiteDifferenceJacobian(system, z, 1e-6);
  EXPECT_LT((j - fd).cwiseAbs().maxCoeff(), 1e-7 * std::max(1.0, fd.cwiseAbs().maxCoeff()));
  EXPECT_GT(j.col(system.omegaIndex()).norm(), 0.1);  // the columns checked are not empty
  EXPECT_GT(j.col(system.xiIndex()).norm(), 0.1);
}

TEST(ModeSystem, LawOmegaColumnMatchesFiniteDifferencesForAVelocityLaw) {
  // Elastic dry friction (uses ẋ and λ̇) on its sliding branch, projection
  // form, on one DOF: the law rows' ω column is analytic.
  HbModel model = oneDof(1.0, 0.0, 1.0, HarmonicKind::kOdd, 3, 64);
  model.laws.push_back({{0}, std::make_shared<Jenkins>(1, 1.0, 5.0, FrictionForm::kProjection, RhoSetting(0.7))});
  FullModeSystem system(model, linearModes(model)[0].shape);
  system.setAmplitude(2.0);
  Eigen::VectorXd z = Eigen::VectorXd::LinSpaced(system.size(), 0.37, -0.21);
  z[0] = 2.0;  // x mostly the fundamental: slips over most of the period
  z[system.omegaIndex()] = 1.3;
  z[system.xiIndex()] = 0.02;
  Eigen::VectorXd g(system.size());
  Eigen::MatrixXd j(system.size(), system.size());
  ASSERT_TRUE(system.residualAndJacobian(z, g, j));
  const Eigen::MatrixXd fd = test::finiteDifferenceJacobian(system, z, 1e-7);
  const int w = system.omegaIndex();
  EXPECT_LT((j.col(w) - fd.col(w)).cwiseAbs().maxCoeff(), 1e-5 * fd.col(w).cwiseAbs().maxCoeff());
  EXPECT_GT(fd.col(w).tail(system.size() - 2 - 6).norm(), 1e-3);  // the law rows move with ω
}

TEST(ModePathSystem, JacobianMatchesFiniteDifferencesIncludingTheLogAmplitudeColumn) {
  // The cubic chain of the mode system's test, in shape coordinates with
  // s = log a unknown, bordered by an arclength row with every weight set.
  HbModel model = rayleighChain(0.03, 0.01);
  model.laws.push_back({{1}, std::make_shared<CubicStiffness>(0.7)});
  model.basis = HarmonicSet(HarmonicKind::kAll, 3);
  model.samples = 32;
  FullModeSystem mode(model, linearModes(model)[0].shape);
  ModePathSystem path(mode);
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(path.size(), -0.3, 0.5);
  y[mode.omegaIndex()] = 0.9;
  y[mode.xiIndex()] = 0.05;
  y[path.sIndex()] = std::log(0.4);
  const PathWeights weights = PathWeights::at(mode, y, 0.05, 0.2);
  path.setConstraint(weights, Eigen::VectorXd::LinSpaced(path.size(), 1.0, 2.0), y * 1.01);
  Eigen::VectorXd g(path.size());
  Eigen::MatrixXd j(path.size(), path.size());
  ASSERT_TRUE(path.residualAndJacobian(y, g, j));
  const Eigen::MatrixXd fd = test::finiteDifferenceJacobian(path, y, 1e-7);
  EXPECT_LT((j - fd).cwiseAbs().maxCoeff(), 1e-6 * std::max(1.0, fd.cwiseAbs().maxCoeff()));
  EXPECT_GT(j.col(path.sIndex()).head(mode.size()).norm(), 0.1);  // the amplitude moves the equations
  // z(y) is the mode system's point: the same residual there.
  Eigen::VectorXd g_mode(mode.size());
  mode.setAmplitude(0.4);
  ASSERT_TRUE(mode.residual(path.modePoint(y), g_mode));
  EXPECT_LT((g.head(mode.size()) - g_mode).cwiseAbs().maxCoeff(), 1e-12 * std::max(1.0, g_mode.norm()));
  EXPECT_LT((path.pathPoint(path.modePoint(y), 0.4) - y).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Backbone, LinearStructureKeepsItsModalFrequencyAndDampingRatioAtEveryAmplitude) {
  const HbModel model = rayleighChain(0.01, 0.004);
  // Reference: the eigenproblem of (K, M), ζ = (α/ω + β ω) / 2.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Eigen::MatrixXd(model.structure.stiffness),
                                                                   Eigen::MatrixXd(model.structure.mass));
  for (int mode = 1; mode <= 2; ++mode) {
    const double omega = std::sqrt(eigen.eigenvalues()[mode - 1]);
    const double zeta = 0.5 * (0.01 / omega + 0.004 * omega);
    const Backbone b = backboneOf(model, mode, 1e-3, 1e3, 7);
    ASSERT_TRUE(b.complete());
    for (const BackbonePoint& p : b.points) {
      EXPECT_NEAR(p.omega, omega, 1e-10 * omega) << "mode " << mode << " at a = " << p.amplitude;
      EXPECT_NEAR(p.damping_ratio, zeta, 1e-10 * zeta) << "mode " << mode << " at a = " << p.amplitude;
      // A linear mode dissipates 2π ζ ω² a² per cycle (ξ π ω a² with ξ = 2ζω).
      EXPECT_NEAR(p.dissipated_energy, 2.0 * M_PI * zeta * omega * omega * p.amplitude * p.amplitude,
                  1e-9 * p.dissipated_energy);
    }
  }
}

// Describing function of a Jenkins element (elastic–perfectly plastic,
// Masing) under x = a cos θ above slip onset a > μN/k_t:
//   in-phase stiffness  k_eq = (k_t / π) (β − sin(2β) / 2),  cos β = 1 − 2 μN / (k_t a),
//   energy per cycle    W = 4 μN (a − μN / k_t).
// The element sits beside a spring k = 10 k_t, which keeps the motion close
// to the harmonic the closed form assumes; the mode's k_eq is ω² m − k.
TEST(Backbone, JenkinsElementFollowsItsDescribingFunctionAboveSlipOnset) {
  const double mu_n = 1.0, k_t = 5.0, k = 50.0;
  HbModel model = oneDof(1.0, 0.0, k, HarmonicKind::kOdd, 30, 2048);
  model.laws.push_back({{0}, std::make_shared<Jenkins>(1, mu_n, k_t, FrictionForm::kMinMax)});
  const Backbone b = backboneOf(model, 1, 0.05, 20.0, 25);
  ASSERT_TRUE(b.complete());
  EXPECT_NEAR(b.start.omega, std::sqrt(k + k_t), 1e-12);  // stuck: the spring k_t in parallel
  double worst_energy = 0.0, worst_stiffness = 0.0;
  int compared = 0, stuck = 0;
  for (const BackbonePoint& p : b.points) {
    const double a = p.full[0];  // the fundamental's cos coefficient (sin: 0 by the phase condition)
    EXPECT_NEAR(a, p.amplitude, 1e-9 * p.amplitude);
    if (a < mu_n / k_t) {  // still stuck: linear, no dissipation
      ++stuck;
      EXPECT_NEAR(p.omega, std::sqrt(k + k_t), 1e-9);
      EXPECT_NEAR(p.dissipated_energy, 0.0, 1e-9);
      continue;
    }
    if (a < 2.0 * mu_n / k_t) continue;  // the kink of the closed form at onset
    const double beta = std::acos(1.0 - 2.0 * mu_n / (k_t * a));
    const double k_eq = k_t / M_PI * (beta - 0.5 * std::sin(2.0 * beta));
    const double energy = 4.0 * mu_n * (a - mu_n / k_t);
    ++compared;
    worst_energy = std::max(worst_energy, std::abs(p.dissipated_energy - energy) / energy);
    worst_stiffness = std::max(worst_stiffness, std::abs(p.omega * p.omega - k - k_eq) / k_t);
  }
  // Measured: energy 5.0e-3 and k_eq 1.5e-3 k_t at H = 30 (1.2e-2 and 1.2e-2
  // k_t at H = 15, 2.4e-3 and 5e-4 k_t at H = 60): the truncation of the
  // kinked force, shrinking as 1/H.
  std::printf("Jenkins: worst error, energy %.3g (relative), k_eq %.3g (of k_t)\n", worst_energy, worst_stiffness);
  EXPECT_GE(compared, 15);
  EXPECT_GE(stuck, 5);
  EXPECT_LT(worst_energy, 7.5e-3);
  EXPECT_LT(worst_stiffness, 3e-3);
}

// Duffing x'' + x + ε x³ = 0: ω² = 1 + (3/4) ε a² + O(ε² a⁴) (Lindstedt:
// ω = 1 + 3/8 ε a² − 15/256 ε² a⁴, so the next term of ω² is 3/128 ε² a⁴).
TEST(Backbone, DuffingFollowsItsSmallAmplitudeExpansion) {
  const double epsilon = 0.1;
  HbModel model = oneDof(1.0, 0.0, 1.0, HarmonicKind::kAll, 7, 32);
  model.laws.push_back({{0}, std::make_shared<CubicStiffness>(epsilon)});
  // The remainder checked is 1e-10 of ω² at a = 0.03: a tolerance of 1e-10
  // would let a point started close enough stop before resolving it.
  SolverOptions tight;
  tight.residual_tolerance = 1e-14;
  const Backbone b = backboneOf(model, 1, 0.01, 1.0, 9, tight);
  ASSERT_TRUE(b.complete());
  for (const BackbonePoint& p : b.points) {
    const double a = p.full[1];  // the fundamental's cos coefficient (basis 0, 1c, 1s, ...)
    const double second = p.omega * p.omega - 1.0 - 0.75 * epsilon * a * a;
    const double scale = std::pow(epsilon * a * a, 2);
    // The remainder is 3/128 (ε a²)² up to the next order, ε a² of it
    // (measured 0.02344 at a = 0.03, 0.02330 at 0.32).
    if (a >= 0.03 && a <= 0.5) {
      EXPECT_NEAR(second / scale, 3.0 / 128.0, (1e-3 + epsilon * a * a) * 3.0 / 128.0) << "a = " << a;
    }
    EXPECT_LT(std::abs(second), 0.03 * scale + 1e-10) << "a = " << a;
    EXPECT_NEAR(p.damping_ratio, 0.0, 1e-12);
  }
}

// Stuck, DOF 2 is held and DOF 1 vibrates at √2, above DOF 2's own
// frequency 1 (DOF 1 held): once DOF 2 slips it moves against DOF 1, so the
// mode ends on the free chain's out-of-phase mode, ω = 1.618.
TEST(Backbone, ExactCoulombGoesFromTheStuckModeToTheFreeOneWithDampingPeakingBetween) {
  const Scene scene = loadScene(test::problem("friction-1d.toml"));
  const Backbone b = backboneOf(scene.model, 1, 0.1, 1e4, 41);
  // Stuck (DOF 2 held): ω² = 2, C = 0.02 K gives ζ = 0.02 ω / 2.
  EXPECT_NEAR(b.start.omega, std::sqrt(2.0), 1e-12);
  ASSERT_TRUE(b.complete());
  const BackbonePoint& first = b.points.front();
  const BackbonePoint& last = b.points.back();
  EXPECT_NEAR(first.omega, std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(first.damping_ratio, 0.01 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(first.dissipated_energy, 2.0 * M_PI * first.damping_ratio * 2.0 * 0.01, 1e-9);  // 2πζω²a²
  // Free chain's second mode: ω = 1.618, ζ = 0.02 ω / 2; friction's share
  // fades as μN / a.
  const double free_omega = (std::sqrt(5.0) + 1.0) / 2.0;
  EXPECT_NEAR(last.omega, free_omega, 1e-4 * free_omega);
  EXPECT_NEAR(last.damping_ratio, 0.01 * free_omega, 0.02 * 0.01 * free_omega);
  double peak = 0.0;
  for (const BackbonePoint& p : b.points) peak = std::max(peak, p.damping_ratio);
  std::printf("friction-1d: zeta %.5g (stuck) -> peak %.5g -> %.5g (a = 1e4)\n", first.damping_ratio, peak,
              last.damping_ratio);
  EXPECT_GT(peak, 3.0 * first.damping_ratio);
  EXPECT_GT(peak, 3.0 * last.damping_ratio);
  for (size_t i = 1; i < b.points.size(); ++i)
    EXPECT_GE(b.points[i].omega, b.points[i - 1].omega * (1.0 - 1e-9));  // from √2 up to 1.618
}

// NLvib's example 05 with the exact Coulomb law, undamped: DOF 1 held at
// small amplitude (ω² = 640 with m₂ = 1), its antiresonance, where a ρ made
// from the dynamic compliance would vanish; sliding freely at large
// amplitude (the free chain's first mode). With ρ from the dynamic
// compliance 23 of these 30 amplitudes failed; stepping in amplitude lost
// one, in the sharp turn at the onset of slip (a = 0.155), which the path
// in arclength passes.
TEST(Backbone, NlvibExampleFiveGoesFromStuckToSliding) {
  const Scene scene = loadScene(test::problem("field/modes/nlvib-05-2dof-friction-modes.toml"));
  const Backbone b = backboneOf(scene.model, 1, 0.0316, 10.0, 30);
  EXPECT_NEAR(b.start.omega, std::sqrt(640.0), 1e-10);
  EXPECT_EQ(b.failed_points, 0);
  // The free chain: 0.02 λ² − 52.8 λ + 24000 = 0, λ = ω².
  const double free_omega = std::sqrt((52.8 - std::sqrt(52.8 * 52.8 - 4.0 * 0.02 * 24000.0)) / 0.04);
  EXPECT_NEAR(b.points.front().omega, std::sqrt(640.0), 1e-9);
  EXPECT_LT(b.points.back().omega, std::sqrt(640.0) - 0.9 * (std::sqrt(640.0) - free_omega));
  double peak = 0.0;
  for (const BackbonePoint& p : b.points) peak = std::max(peak, p.damping_ratio);
  EXPECT_GT(peak, 0.01);  // friction damps the mode while it slips
  EXPECT_LT(b.points.back().damping_ratio, 0.5 * peak);
}

// beam-damper's first mode turns back in amplitude at a = 7.80e-4 (ω =
// 28.95, ζ = 0.52): just below it two modes share an amplitude. Stepping in
// amplitude failed there or jumped between them; the path passes the fold
// and records both modes at the grid amplitude 7.6e-4, on its way up and
// on its way back.
TEST(Backbone, BeamDamperPassesTheFoldWhereTheBackboneTurnsBackInAmplitude) {
  const Scene scene = loadScene(test::problem("beam-damper.toml"));
  auto solver = makeSolver("dogleg");
  BackboneOptions o;
  o.from = 7.6e-5;
  o.to = 7.6e-4 * std::cbrt(10.0);
  o.points = 5;
  o.max_halvings = 2;  // the path stops further on (ζ = 1.4): no need to insist there
  const Backbone b = followBackbone(scene.model, *solver, SolverOptions(), o);
  ASSERT_FALSE(b.folds.empty());
  const BackboneFold& fold = b.folds.front();
  std::printf("first fold: a = %.6g, omega = %.6g, zeta = %.4g; %zu folds\n", fold.amplitude, fold.omega,
              fold.damping_ratio, b.folds.size());
  EXPECT_NEAR(fold.amplitude, 7.80e-4, 0.01 * 7.80e-4);
  EXPECT_NEAR(fold.omega, 28.95, 0.1);
  EXPECT_NEAR(fold.damping_ratio, 0.516, 0.01);
  std::vector<const BackbonePoint*> below_fold;
  for (const BackbonePoint& p : b.points)
    if (p.converged && std::abs(p.amplitude - 7.6e-4) < 1e-9 * 7.6e-4) below_fold.push_back(&p);
  ASSERT_GE(below_fold.size(), 2u);
  // Up the first branch: stiffer and less damped than back down the second.
  EXPECT_GT(below_fold[0]->omega, fold.omega + 0.3);
  EXPECT_LT(below_fold[1]->omega, fold.omega - 0.3);
  EXPECT_LT(below_fold[0]->damping_ratio, below_fold[1]->damping_ratio);
  for (size_t i = 1; i < b.points.size(); ++i)  // the path's order: 7.6e-4 up, then back, never skipped
    if (b.points[i].amplitude < b.points[i - 1].amplitude) EXPECT_EQ(&b.points[i - 1], below_fold[0]);
}

// beam-damper's sliding branch: the free beam's mode 1 (ω = 1.8751² with
// EI = ρA = L = 1) followed down from large amplitude, the five dampers
// sliding. Its ω and ζ at a = 0.3 and 3 are those solved there at fixed
// amplitude from the free mode (3.4270, 0.267; 3.5151, 0.030); the forced
// resonance (ω 3.504) lies on it. The held branch from ω 57.5 folds five
// times and heads for the free beam's mode 2 instead.
TEST(Backbone, BeamDamperSlidingBranchIsTheFreeBeamsFirstModeDownFromLargeAmplitude) {
  const Scene scene = loadScene(test::problem("beam-damper.toml"));
  auto solver = makeSolver("dogleg");
  BackboneOptions o;
  o.branch = ModeBranch::kSliding;
  o.from = 0.3;
  o.to = 3.0;
  o.points = 5;
  const Backbone b = followBackbone(scene.model, *solver, SolverOptions(), o);
  EXPECT_EQ(b.branch, ModeBranch::kSliding);
  EXPECT_NEAR(b.start.omega, 1.8751040687 * 1.8751040687, 1e-3);
  ASSERT_TRUE(b.complete());
  ASSERT_EQ(b.points.size(), 5u);
  EXPECT_NEAR(b.points.front().amplitude, 0.3, 1e-12);
  EXPECT_NEAR(b.points.back().amplitude, 3.0, 1e-12);
  EXPECT_NEAR(b.points.front().omega, 3.4270, 2e-4);
  EXPECT_NEAR(b.points.front().damping_ratio, 0.267, 1e-3);
  EXPECT_NEAR(b.points.back().omega, 3.5151, 2e-4);
  EXPECT_NEAR(b.points.back().damping_ratio, 0.030, 1e-3);
  for (size_t i = 1; i < b.points.size(); ++i) {  // increasing amplitude: stiffer, less damped
    EXPECT_GT(b.points[i].amplitude, b.points[i - 1].amplitude);
    EXPECT_GT(b.points[i].omega, b.points[i - 1].omega);
    EXPECT_LT(b.points[i].damping_ratio, b.points[i - 1].damping_ratio);
  }
}

// `eqhb modes` by default: beam-damper's sweep (2.8 .. 4.4) holds the free
// beam's mode 1 and not the held one (57.5), so its mode 1 is the sliding
// branch, 50 amplitudes all converged; blade-tip-damper's holds both (1389.5
// held, 656.2 free), so its mode 1 is the held branch, whose default range
// now starts below the pressed damper's slip onset (its static μN over the
// mode's tangential force): stuck at 1389.52 there, then sliding to 656.4
// (before: from 4.2e-4, the first amplitude failed and the rest were already
// at 657).
TEST(Backbone, DefaultBranchIsTheOneTheScenesSweepHolds) {
  app::SceneSettings beam;
  beam.path = test::problem("beam-damper.toml");
  const app::ModesRun b = app::modes(beam, app::ModesOptions());
  EXPECT_EQ(b.backbone.branch, ModeBranch::kSliding);
  EXPECT_EQ(b.backbone.points.size(), 50u);
  EXPECT_TRUE(b.backbone.complete()) << b.backbone.failed_points << " failed";
  EXPECT_NEAR(b.backbone.points.back().omega, 3.516, 1e-3);
  std::printf("beam-damper sliding: %zu points, %d failed, %.3g s\n", b.backbone.points.size(),
              b.backbone.failed_points, b.backbone.seconds);

  app::SceneSettings blade;
  blade.path = test::problem("blade-tip-damper.toml");
  const app::ModesRun t = app::modes(blade, app::ModesOptions());
  EXPECT_EQ(t.backbone.branch, ModeBranch::kHeld);
  EXPECT_TRUE(t.backbone.complete()) << t.backbone.failed_points << " failed";
  ASSERT_FALSE(t.backbone.points.empty());
  EXPECT_NEAR(t.backbone.points.front().omega, 1389.52, 0.01);
  EXPECT_NEAR(t.backbone.points.back().omega, 656.4, 0.5);

  app::ModesOptions bad;
  bad.branch = "stuck";
  EXPECT_THROW(app::modes(beam, bad), InputError);
}

// A time limit for the whole backbone stops the path and says so; the
// amplitudes it did not reach are failed points (beam-damper's backbone
// takes seconds: it stalls past its folds).
TEST(Backbone, TimeLimitStopsThePathAndFailsTheAmplitudesNotReached) {
  const Scene scene = loadScene(test::problem("beam-damper.toml"));
  auto solver = makeSolver("dogleg");
  BackboneOptions o;
  o.from = 7.6e-7;
  o.to = 7.6e-2;
  o.points = 30;
  o.time_limit = 0.2;
  const Backbone b = followBackbone(scene.model, *solver, SolverOptions(), o);
  EXPECT_NE(b.stop.why.find("time limit of 0.2 s"), std::string::npos) << b.stop.why;
  ASSERT_GT(b.failed_points, 0);
  EXPECT_FALSE(b.points.back().converged);
  EXPECT_EQ(b.points.back().termination, b.stop.why);
  EXPECT_LT(b.seconds, 3.0);  // not a speed target: the unlimited backbone takes 4-17 s
  o.time_limit = -1.0;
  EXPECT_THROW(followBackbone(scene.model, *solver, SolverOptions(), o), InputError);
}

// NLvib's example 02 chain with its cubic spring between DOFs 1 and 2, and
// with exact Coulomb friction between them: the same structure in the
// coordinates y = (x1, x1 − x2), where both elements are grounded, has the
// same backbone (the modal amplitude φᵀ M x̂₁ does not depend on the
// coordinates). Coulomb ties the two DOFs at small amplitude.
TEST(Backbone, ElementsBetweenTwoNodesGiveTheBackboneOfTheSameStructureInGroundedCoordinates) {
  Eigen::MatrixXd m(2, 2), c(2, 2), k(2, 2), t(2, 2);
  m << 1.0, 0.0, 0.0, 0.05;
  c << 0.015, -0.013, -0.013, 0.013;
  k << 1.0453, -0.0453, -0.0453, 0.0453;
  t << 1.0, 0.0, 1.0, -1.0;  // x = T y
  const std::vector<Eigen::VectorXd> along = {Eigen::VectorXd::Ones(1)};
  for (const bool friction : {false, true}) {
    HbModel relative = oneDof(1.0, 0.0, 1.0, HarmonicKind::kOdd, 5, 64);
    relative.structure = LinearStructure::fromMassStiffnessDamping(m, k, c);
    HbModel grounded = relative;
    grounded.structure =
        LinearStructure::fromMassStiffnessDamping(t.transpose() * m * t, t.transpose() * k * t, t.transpose() * c * t);
    relative.laws.push_back({{0}, std::make_shared<CubicStiffness>(1.0)});
    grounded.laws.push_back({{0}, std::make_shared<CubicStiffness>(1.0)});
    std::shared_ptr<Law> between = std::make_shared<CubicStiffness>(0.0042);
    if (friction) between = std::make_shared<Coulomb1D>(0.05, CoulombForm::kMinMax);
    relative.laws.push_back({LawAttachment::relative({0}, {1}, along), between});
    grounded.laws.push_back({{1}, between});
    ASSERT_FALSE(relative.laws.back().attachment.grounded());
    const Backbone a = backboneOf(relative, 1, 0.01, friction ? 20.0 : 1.0, 9);
    const Backbone b = backboneOf(grounded, 1, 0.01, friction ? 20.0 : 1.0, 9);
    EXPECT_NEAR(a.start.omega, b.start.omega, 1e-12);
    ASSERT_TRUE(a.complete());
    ASSERT_TRUE(b.complete());
    ASSERT_EQ(a.points.size(), b.points.size());
    double spread = 0.0;
    for (size_t i = 0; i < a.points.size(); ++i) {
      EXPECT_NEAR(a.points[i].omega, b.points[i].omega, 1e-8 * b.points[i].omega) << i;
      EXPECT_NEAR(a.points[i].damping_ratio, b.points[i].damping_ratio, 1e-8) << i;
      spread = std::max(spread, std::abs(a.points[i].omega - a.points.front().omega));
    }
    EXPECT_GT(spread, 0.01) << "the range reaches the nonlinear regime";
  }
}

TEST(Backbone, RefusesAModeAboveTheStructuresAndABadAmplitudeRange) {
  const HbModel model = rayleighChain(0.01, 0.004);
  auto solver = makeSolver("dogleg");
  auto message = [&](BackboneOptions o) {
    try {
      followBackbone(model, *solver, SolverOptions(), o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  BackboneOptions o;
  o.from = 0.1;
  o.to = 1.0;
  o.mode = 3;
  EXPECT_NE(message(o).find("mode = 3"), std::string::npos) << message(o);
  o.mode = 1;
  o.from = 0.0;
  EXPECT_NE(message(o).find("from = 0"), std::string::npos) << message(o);
  o.from = std::nan("");
  EXPECT_NE(message(o).find("from"), std::string::npos) << message(o);
  o.from = 1.0;
  o.to = 0.5;
  EXPECT_NE(message(o).find("to = 0.5"), std::string::npos) << message(o);
}

}  // namespace
}  // namespace eqhb
