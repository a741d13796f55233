#include "eqhb/stability/hill_stability.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>

#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/stability/curve_stability.h"
#include "test_support.h"

namespace eqhb {
namespace {

using Complex = std::complex<double>;

Eigen::VectorXd solveFull(const HbModel& model, const Eigen::VectorXd& start = {}) {
  auto system = makeHbSystem(model, false);
  SolverOptions options;
  options.residual_tolerance = 1e-11;
  const Eigen::VectorXd z0 = start.size() ? start : Eigen::VectorXd::Zero(system->size());
  const auto result = makeSolver("dogleg")->solve(*system, z0, options);
  EXPECT_TRUE(result.converged());
  return system->fullCoefficients(result.solution);
}

// Multipliers sorted by (modulus, argument) for a set comparison.
std::vector<Complex> sorted(std::vector<Complex> v) {
  std::sort(v.begin(), v.end(), [](Complex a, Complex b) {
    if (std::abs(std::abs(a) - std::abs(b)) > 1e-9) return std::abs(a) > std::abs(b);
    return std::arg(a) < std::arg(b);
  });
  return v;
}

std::vector<Complex> hillMultipliers(const HillResult& r) {
  std::vector<Complex> v;
  for (const auto& e : r.exponents) v.push_back(e.multiplier);
  return sorted(v);
}

// exp(λ T) for the eigenvalues λ of the first-order linear system.
std::vector<Complex> linearMultipliers(const LinearStructure& s, double omega) {
  const int n = s.dofs();
  const Eigen::MatrixXd m = Eigen::MatrixXd(s.mass), c = Eigen::MatrixXd(s.damping), k = Eigen::MatrixXd(s.stiffness);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n).setIdentity();
  a.bottomLeftCorner(n, n) = -m.inverse() * k;
  a.bottomRightCorner(n, n) = -m.inverse() * c;
  const Eigen::VectorXcd lambda = a.eigenvalues();
  std::vector<Complex> rho;
  for (int i = 0; i < 2 * n; ++i) rho.push_back(std::exp(lambda[i] * 2.0 * M_PI / omega));
  return sorted(rho);
}

void expectSameMultipliers(const std::vector<Complex>& hill, const std::vector<Complex>& exact, double tolerance) {
  ASSERT_EQ(hill.size(), exact.size());
  // Match greedily (the order of equal moduli may differ).
  std::vector<bool> used(exact.size(), false);
  for (const Complex& h : hill) {
    double best = 1e300;
    size_t at = 0;
    for (size_t j = 0; j < exact.size(); ++j)
      if (!used[j] && std::abs(h - exact[j]) < best) best = std::abs(h - exact[j]), at = j;
    used[at] = true;
    EXPECT_LT(best, tolerance) << "Hill multiplier " << h << " vs " << exact[at];
  }
}

// The 2-DOF chain of the scenes with a cubic law of stiffness ε (0: linear).
HbModel chain(double epsilon, HarmonicKind kind, int harmonics, double omega, double damping = 0.02) {
  HbModel model;
  Eigen::MatrixXd t(2, 2);
  t << 2, -1, -1, 1;
  model.structure = LinearStructure::fromMassStiffnessDamping(Eigen::MatrixXd::Identity(2, 2), t, damping * t);
  model.structure.loads.push_back({0, 1, 1.0, 0.0});
  model.laws.push_back({{1}, std::make_shared<CubicStiffness>(epsilon)});
  model.basis = HarmonicSet(kind, harmonics);
  model.samples = 64;
  model.omega = omega;
  return model;
}

TEST(HillStability, LinearChainGivesTheExactMultipliers) {
  // Linear: the Hill matrix is block diagonal per harmonic and each block
  // has the exponents λ − i k ω exactly, on either basis.
  for (HarmonicKind kind : {HarmonicKind::kAll, HarmonicKind::kOdd})
    for (double omega : {0.3, 0.9, 2.1}) {
      const HbModel model = chain(0.0, kind, 4, omega);
      const HillResult r = hillStability(model, solveFull(model));
      ASSERT_TRUE(r.failure.empty()) << r.failure;
      EXPECT_EQ(r.state_dimension, 4);
      expectSameMultipliers(hillMultipliers(r), linearMultipliers(model.structure, omega), 1e-9);
      EXPECT_TRUE(r.stable);
      EXPECT_FALSE(r.sparse);
    }
}

TEST(HillStability, NegativeDampingIsUnstable) {
  const HbModel model = chain(0.0, HarmonicKind::kAll, 3, 0.7, -0.01);
  const HillResult r = hillStability(model, solveFull(model));
  expectSameMultipliers(hillMultipliers(r), linearMultipliers(model.structure, 0.7), 1e-9);
  EXPECT_FALSE(r.stable);
  EXPECT_GT(r.spectral_radius, 1.0);
}

TEST(HillStability, SparseArnoldiAgreesWithDense) {
  const HbModel model = chain(0.5, HarmonicKind::kOdd, 6, 0.5);
  const Eigen::VectorXd full = solveFull(model);
  const HillResult dense = hillStability(model, full);
  HillOptions options;
  options.dense_limit = 0;
  const HillResult sparse = hillStability(model, full, options);
  EXPECT_TRUE(sparse.sparse);
  ASSERT_TRUE(sparse.failure.empty()) << sparse.failure;
  expectSameMultipliers(hillMultipliers(sparse), hillMultipliers(dense), 1e-8);
}

TEST(HillStability, CubicMultipliersApproachTheShootingOnes) {
  HbModel model = loadScene(test::problem("cubic.toml")).model;  // ω = 0.5
  const auto flow = orbits::makeFlow(model, 0.0);
  const Eigen::VectorXd hb = solveFull(model);
  const auto orbit = orbits::shootFromHarmonicBalance(*flow, model, hb, {});
  ASSERT_TRUE(orbit.converged);
  std::vector<Complex> exact(orbit.multipliers.data(), orbit.multipliers.data() + orbit.multipliers.size());
  const HillResult r = hillStability(model, hb);
  expectSameMultipliers(hillMultipliers(r), sorted(exact), 1e-6);
  EXPECT_EQ(r.stable, orbit.stable);
}

// The cubic chain's curve across both folds, for the curve tests below.
ContinuationOptions cubicCurveRange() {
  ContinuationOptions options;
  options.from = 0.4;
  options.to = 1.6;
  options.step = 0.02;
  return options;
}

TEST(HillStability, DuffingCurveAgreesWithShootingAndTheMiddleBranchIsUnstable) {
  // The hardening chain bends right and folds twice: the branch between the
  // two turning points is unstable and a real multiplier passes +1 at each
  // fold. Elsewhere the chain has further unstable stretches (a complex pair
  // outside near ω = 0.65, a real multiplier > 1 near ω = 1.0, confirmed by
  // shooting), so every sampled point is checked against the exact
  // multipliers of the shooting orbit.
  const Scene scene = loadScene(test::problem("cubic.toml"));
  const ContinuationOptions options = cubicCurveRange();
  auto solver = makeSolver("dogleg");
  const Curve curve = sweepArclength(scene.model, *solver, SolverOptions(), options);
  ASSERT_EQ(curve.fold_omegas.size(), 2u) << curve.stop_reason;
  std::vector<int> folds;
  for (int i = 0; i < static_cast<int>(curve.points.size()); ++i)
    if (curve.points[i].fold) folds.push_back(i);
  ASSERT_EQ(folds.size(), 2u);
  int middle_points = 0, unstable_elsewhere = 0, stable_points = 0;
  std::map<int, HillResult> results;
  // About 60 points spread along the curve and the neighbours of the folds.
  const int stride = std::max(1, static_cast<int>(curve.points.size()) / 60);
  for (int i = 0; i < static_cast<int>(curve.points.size()); ++i) {
    const bool near_fold = std::abs(i - folds[0]) <= 1 || std::abs(i - folds[1]) <= 1;
    if (i % stride != 0 && !near_fold) continue;
    HbModel model = scene.model;
    model.omega = curve.points[i].omega;
    const HillResult& r = results[i] = hillStability(model, curve.points[i].full);
    ASSERT_TRUE(r.failure.empty()) << r.failure;
    ASSERT_EQ(r.exponents.size(), 4u) << "omega " << model.omega << " point " << i << " near fold " << near_fold;
    if (near_fold) continue;  // the tangent and the multiplier cross within a step
    const bool middle = i > folds[0] && i < folds[1];
    if (middle) {
      EXPECT_FALSE(r.stable) << "middle branch, omega " << model.omega;
      ++middle_points;
    }
    const auto flow = orbits::makeFlow(model, 0.0);
    const auto orbit = orbits::shootFromHarmonicBalance(*flow, model, curve.points[i].full, {});
    ASSERT_TRUE(orbit.converged) << orbit.failure;
    EXPECT_EQ(r.stable, orbit.stable) << "omega " << model.omega;
    EXPECT_NEAR(r.spectral_radius / orbit.spectral_radius, 1.0, 2e-3) << "omega " << model.omega;
    if (!r.stable && !middle) ++unstable_elsewhere;
    if (r.stable) ++stable_points;
  }
  EXPECT_GE(middle_points, 2);
  EXPECT_GE(unstable_elsewhere, 1);
  EXPECT_GE(stable_points, 2);
  // The stability change at a turning point is a fold: a real multiplier through +1.
  for (int f : folds) {
    const std::string kind = bifurcationKind(results[f - 1], results[f]) + bifurcationKind(results[f], results[f + 1]);
    EXPECT_EQ(kind, "fold") << "at point " << f;
    for (int j = f - 1; j <= f + 1; ++j) {
      double nearest = 1e300;
      for (const auto& e : results[j].exponents) nearest = std::min(nearest, std::abs(e.multiplier - 1.0));
      EXPECT_LT(nearest, 0.6) << "point " << j;  // steps are long at the lower fold
    }
  }
}

// A curve's stability under a time limit: the points reached get their
// verdicts, the rest none, and the result says how many were analysed; no
// limit analyses every converged point; progress is told of each point
// analysed. A limit below zero or not finite is
// refused naming it.
TEST(HillStability, ACurvesStabilityStopsAtItsTimeLimit) {
  const Scene scene = loadScene(test::problem("cubic.toml"));
  const ContinuationOptions options = cubicCurveRange();
  auto solver = makeSolver("dogleg");
  Curve curve = sweepSequential(scene.model, *solver, SolverOptions(), options);
  int converged = 0;
  for (const CurvePoint& p : curve.points) converged += p.converged;
  ASSERT_GT(converged, 20);
  // Progress after each point analysed: the points done so far of the curve's.
  std::vector<int> done;
  auto progress = [&](int d, int total) {
    EXPECT_EQ(total, static_cast<int>(curve.points.size()));
    EXPECT_TRUE(done.empty() || d > done.back()) << d;
    done.push_back(d);
  };
  const CurveStability all = analyseCurveStability(scene.model, curve, {}, progress);
  EXPECT_FALSE(all.time_limited);
  EXPECT_EQ(all.analysed, converged);
  EXPECT_EQ(static_cast<int>(done.size()), converged);
  HillOptions limited;
  limited.time_limit = 1e-9;  // out of time at the first check
  done.clear();
  const CurveStability some = analyseCurveStability(scene.model, curve, limited, progress);
  EXPECT_TRUE(some.time_limited);
  EXPECT_LT(some.analysed, converged);
  EXPECT_EQ(static_cast<int>(done.size()), some.analysed);
  int verdicts = 0;
  for (const CurvePoint& p : curve.points) verdicts += p.stable.has_value();
  EXPECT_EQ(verdicts, some.analysed);
  for (double bad : {-1.0, std::nan(""), HUGE_VAL}) {
    HillOptions o;
    o.time_limit = bad;
    try {
      o.validate();
      ADD_FAILURE() << "accepted time_limit = " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("stability_time_limit"), std::string::npos) << e.what();
    }
  }
}

// The damper's two contact faces stick and stay closed over parts of the
// period: the pencil's infinite eigenvalues are defective there and come out
// of rounding at |s| of 1e7–1e8 ω with positive real parts. They must not be
// taken for Floquet exponents (they were: infinite multipliers, "unstable").
TEST(HillStability, DefectiveInfiniteEigenvaluesOfConstraintsAreNotExponents) {
  const Scene scene = loadScene(test::problem("damper.toml"), {"harmonic_balance.omega=0.86"});
  CondensedSystem system(scene.model);
  const auto solved = makeSolver("dogleg")->solve(system, Eigen::VectorXd::Zero(system.size()), {});
  ASSERT_TRUE(solved.converged()) << solved.summary();
  const HillResult r = hillStability(scene.model, system.fullCoefficients(solved.solution));
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  ASSERT_EQ(static_cast<int>(r.exponents.size()), r.state_dimension);
  for (const auto& e : r.exponents) {
    EXPECT_LT(std::abs(e.exponent), 100.0 * 0.86) << e.exponent;
    EXPECT_TRUE(std::isfinite(std::abs(e.multiplier))) << e.exponent;
  }
  EXPECT_TRUE(r.stable) << r.spectral_radius;
  EXPECT_NEAR(r.spectral_radius, 0.9648, 1e-3);
}

TEST(HillStability, RejectsASolutionOfTheWrongSize) {
  const HbModel model = chain(0.0, HarmonicKind::kAll, 2, 0.5);
  EXPECT_THROW(hillStability(model, Eigen::VectorXd::Zero(3)), InputError);
}

}  // namespace
}  // namespace eqhb
