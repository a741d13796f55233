// The bolted lap joint (problems/lap-joint.toml) against its linear limits:
// under small forcing every slider sticks and the response is the linear
// system with the tangential springs k_t; under large forcing the sliders
// slide at their limit and the response tends to the system without them;
// and the energy the forcing feeds in per cycle is what the damping and the
// contacts take out.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "eqhb/app/modes.h"
#include "eqhb/app/solve.h"
#include "eqhb/continuation/fallback_chain.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/joints/jenkins_aft.h"
#include "eqhb/laws/penalty_contact.h"
#include "eqhb/preload/operating_point.h"
#include "check_support.h"

namespace eqhb {
namespace {

constexpr int kForcedDof = 58;  // 0-based: the upper beam's w at pair 11 (mid-span)
constexpr int kPreloads = 42;   // two per pair

// The scene at `omega` under forcing `force`, reached by continuation in the
// force from `from` (a stuck response, solved from the static state) in
// steps of at most `ratio`: a solve from the static state straight into
// microslip near the resonance stalls or finds a spurious harmonic-balance
// solution (see the scene's header).
std::vector<app::Solution> solveLap(const std::vector<double>& forces, double omega,
                                    const std::vector<std::string>& overrides = {},
                                    const std::string& fallback = "none") {
  app::SceneSettings scene;
  scene.path = test::problem("lap-joint.toml");
  scene.omega = omega;
  app::SolveOptions options;
  options.fallback = fallback;
  std::vector<app::Solution> out;
  double level = std::min(2.0, forces.front());
  for (double force : forces) {
    while (true) {
      scene.overrides = overrides;
      scene.overrides.push_back("forcing[0].cos=" + formatNumber(level));
      app::Solution s = app::solve(scene, options);
      EXPECT_TRUE(s.converged()) << "force " << level << ": " << terminationName(s.run.result.termination);
      if (!s.converged()) return out;
      options.initial = s.full;
      if (level == force) {
        out.push_back(std::move(s));
        break;
      }
      level = std::min(force, 1.5 * level);
    }
  }
  return out;
}

app::Solution solveLap(double force, double omega, const std::vector<std::string>& overrides = {}) {
  std::vector<app::Solution> s = solveLap(std::vector<double>{force}, omega, overrides);
  if (s.empty()) throw std::runtime_error("no solution");
  return std::move(s.back());
}

// The bolt `factor` times the scene's, the friction limits kept.
std::vector<std::string> boltTimes(double factor) {
  const Scene scene = loadScene(test::problem("lap-joint.toml"));
  EXPECT_EQ(scene.preload.size(), static_cast<size_t>(kPreloads));
  std::vector<std::string> out;
  for (int i = 0; i < kPreloads; ++i)
    out.push_back("preload[" + std::to_string(i) + "].force=" + formatNumber(factor * scene.preload[i].cos_amplitude));
  return out;
}

// K with each law a linear spring along its direction: penalty contacts by
// k_n, sliders by k_t when `stuck` (else none).
Eigen::MatrixXd springStiffness(const HbModel& model, bool stuck) {
  const LinearStructure& s = model.structure;
  Eigen::MatrixXd k(s.stiffness);
  for (const AttachedLaw& law : model.laws) {
    double spring = 0.0;
    if (const auto* wall = dynamic_cast<const PenaltyContact*>(law.law.get())) spring = wall->stiffness();
    if (const auto* slider = dynamic_cast<const JenkinsAft*>(law.law.get()); slider && stuck)
      spring = slider->sliders().front().k_t;
    const Eigen::MatrixXd w = law.attachment.transposeDense(s.dofs());  // n x 1
    k += spring * w * w.transpose();
  }
  return k;
}

// The harmonic-1 response (a1 + i b1 per DOF, x = a1 cos ωt + b1 sin ωt) of
// the structure with each law replaced by a linear spring along its
// direction: penalty contacts by k_n, sliders by k_t when `stuck` (else none).
Eigen::VectorXcd linearResponse(const HbModel& model, bool stuck) {
  const LinearStructure& s = model.structure;
  const Eigen::MatrixXd k = springStiffness(model, stuck);
  const double omega = model.omega;
  Eigen::MatrixXcd dynamic = (k - omega * omega * Eigen::MatrixXd(s.mass)).cast<std::complex<double>>();
  dynamic += std::complex<double>(0.0, omega) * Eigen::MatrixXd(s.damping).cast<std::complex<double>>();
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(s.dofs());
  for (const HarmonicLoad& load : s.loads)
    if (load.harmonic == 1) f[load.dof] += std::complex<double>(load.cos_amplitude, -load.sin_amplitude);
  // X = a − i b with x = Re(X e^{iωt}).
  const Eigen::VectorXcd x = dynamic.partialPivLu().solve(f);
  return x.conjugate();
}

// a_k + i b_k of every DOF from full coefficients [x; λ] on `model`'s basis.
Eigen::VectorXcd harmonic(const HbModel& model, const Eigen::VectorXd& full, int k) {
  const int size = model.basis.size(), n = model.structure.dofs();
  Eigen::VectorXcd out(n);
  for (int j = 0; j < n; ++j) out[j] = {full[j * size + 2 * k - 1], full[j * size + 2 * k]};
  return out;
}

Eigen::VectorXcd harmonic(const app::Solution& s, int k) { return harmonic(s.model(), s.full, k); }

TEST(LapJoint, SmallForcingIsTheLinearStuckSystem) {
  const app::Solution s = solveLap(0.1, 1530.0);
  ASSERT_TRUE(s.run.scene.at_rest);
  const Eigen::VectorXcd stuck = linearResponse(s.model(), true);
  const Eigen::VectorXcd x1 = harmonic(s, 1);
  EXPECT_LT((x1 - stuck).cwiseAbs().maxCoeff(), 1e-6 * stuck.cwiseAbs().maxCoeff());
  // Not the sliding system: the sliders' k_t stiffens the first mode.
  const Eigen::VectorXcd sliding = linearResponse(s.model(), false);
  EXPECT_GT((sliding - stuck).cwiseAbs().maxCoeff(), 0.05 * stuck.cwiseAbs().maxCoeff());
  // The mean is the static state; no higher harmonic.
  const int size = s.model().basis.size();
  for (int j = 0; j < s.model().structure.dofs(); ++j) {
    EXPECT_NEAR(s.full[j * size], s.run.scene.at_rest->displacement[j], 1e-9 * stuck.cwiseAbs().maxCoeff());
    for (int k = 2; k <= 7; ++k) EXPECT_LT(std::abs(harmonic(s, k)[j]), 1e-9 * stuck.cwiseAbs().maxCoeff());
  }
}

// With the bolt 20 times the scene's (the lap's end pairs then stay closed)
// and the friction limits kept, the sliders' force is bounded while the
// forcing grows: the response per unit force leaves the stuck system's and
// tends to the linear sliding system's. Once every slider slides, what
// separates the two is the sliders' bounded force over the forcing, so the
// gap falls as 1/f: gap times force levels off.
TEST(LapJoint, LargeForcingTendsToTheSlidingSystem) {
  const std::vector<std::string> bolt = boltTimes(20.0);
  const std::vector<double> forces{10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0};
  // The default path: from about 450 N on, the step from the last force
  // stalls and the start from the static state is what converges.
  const std::vector<app::Solution> solutions = solveLap(forces, 1400.0, bolt, "default");
  ASSERT_EQ(solutions.size(), forces.size());
  std::vector<double> gaps;
  for (const app::Solution& s : solutions) {
    const double force = s.model().structure.loads[0].cos_amplitude;
    const std::complex<double> sliding = linearResponse(s.model(), false)[kForcedDof] / force;
    const std::complex<double> stuck = linearResponse(s.model(), true)[kForcedDof] / force;
    const std::complex<double> x = harmonic(s, 1)[kForcedDof] / force;
    gaps.push_back(std::abs(x - sliding) / std::abs(sliding));
    // Between the two linear limits.
    EXPECT_LT(std::abs(x), std::max(std::abs(sliding), std::abs(stuck)));
    EXPECT_GT(std::abs(x), std::min(std::abs(sliding), std::abs(stuck)));
    std::printf("force %g: |x1|/f = %.6g, sliding %.6g, stuck %.6g, gap to sliding %.3g, gap x force %.4g\n", force,
                std::abs(x), std::abs(sliding), std::abs(stuck), gaps.back(), gaps.back() * force);
  }
  // 10 and 30 N: stuck, the stuck system's gap (0.41 at this omega); then
  // the sliders give way and the gap closes.
  EXPECT_NEAR(gaps[1], gaps[0], 1e-6);
  for (size_t i = 2; i < gaps.size(); ++i) EXPECT_LT(gaps[i], gaps[i - 1]) << "force " << forces[i];
  EXPECT_LT(gaps[3], 0.2);
  // The limit: gap x force at 3000 N within 2 % of its value at 1000 N
  // (53.65 against 53.42).
  const double at1000 = gaps[4] * forces[4], at3000 = gaps[5] * forces[5];
  EXPECT_NEAR(at3000, at1000, 0.02 * at1000);
  EXPECT_LT(gaps[5], 0.02);
}

// Per cycle: the forcing's work π Σ f_c b1 − f_s a1 equals the damping's
// π ω Σ k² (a_kᵀ C a_k + b_kᵀ C b_k) plus what the contacts dissipate,
// −∮ s λ · u̇ dt = −π Σ_k k (c_k β_k − d_k α_k) summed over the laws
// (λ = c_k cos + d_k sin, u = W x = α_k cos + β_k sin). The penalty
// contacts are elastic: the sliders dissipate it all.
TEST(LapJoint, EnergyFedInIsWhatTheDampingAndTheSlidersDissipate) {
  for (double force : {2.0, 15.0}) {
    const app::Solution s = solveLap(force, 1534.0);
    const HbModel& model = s.model();
    const int size = model.basis.size(), n = model.structure.dofs();
    const Eigen::MatrixXd c(model.structure.damping);
    double input = 0.0, damping = 0.0, sliders = 0.0, walls = 0.0;
    for (const HarmonicLoad& load : model.structure.loads)
      if (load.harmonic == 1)
        input += M_PI * (load.cos_amplitude * harmonic(s, 1)[load.dof].imag() -
                         load.sin_amplitude * harmonic(s, 1)[load.dof].real());
    for (int k = 1; k <= 7; ++k) {
      const Eigen::VectorXcd x = harmonic(s, k);
      damping += M_PI * model.omega * k * k *
                 (x.real().dot(c * x.real()) + x.imag().dot(c * x.imag()));
    }
    for (size_t l = 0; l < model.laws.size(); ++l) {
      const AttachedLaw& law = model.laws[l];
      const int lambda = (n + model.componentIndex(static_cast<int>(l), 0)) * size;
      double work = 0.0;
      for (int k = 1; k <= 7; ++k) {
        Eigen::VectorXd cos_x(n), sin_x(n);
        for (int j = 0; j < n; ++j) {
          cos_x[j] = s.full[j * size + 2 * k - 1];
          sin_x[j] = s.full[j * size + 2 * k];
        }
        const double alpha = law.attachment.gather(cos_x, 0), beta = law.attachment.gather(sin_x, 0);
        work += M_PI * k * (s.full[lambda + 2 * k - 1] * beta - s.full[lambda + 2 * k] * alpha);
      }
      (dynamic_cast<const PenaltyContact*>(law.law.get()) ? walls : sliders) -= law.law->forceSign() * work;
    }
    if (force > 2.0) {
      EXPECT_GT(sliders, 0.1 * input) << "force " << force;
    }
    EXPECT_NEAR(input, damping + sliders + walls, 1e-7 * input) << "force " << force;
    EXPECT_LT(std::abs(walls), 1e-6 * input) << "force " << force;
    std::printf("force %g: input %.6g J, damping %.6g J, sliders %.6g J, walls %.3g J\n", force, input, damping,
                sliders, walls);
  }
}

// The first bending frequency of the structure with each law a linear
// spring (springStiffness).
double firstFrequency(const HbModel& model, bool stuck) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(springStiffness(model, stuck),
                                                                         Eigen::MatrixXd(model.structure.mass));
  return std::sqrt(eigen.eigenvalues()[0]);
}

// The dynamic solve's start under the bolt (preload/operating_point.h) is
// the linear stuck system's response about the static state, wherever the
// sliders would overrun their limits on it: at the peak too, where the full
// system's residual there (the laws' violation) exceeds the one at the
// static state (the forcing alone).
TEST(LapJoint, TheStartNearThePeakIsTheLinearStuckResponse) {
  constexpr double kPeak = 1534.0;
  app::SceneSettings settings;
  settings.path = test::problem("lap-joint.toml");
  settings.omega = kPeak;
  Scene scene = app::loadScene(settings);
  ASSERT_TRUE(scene.at_rest);
  const Eigen::VectorXd start = linearisedStart(scene.model, *scene.at_rest, SolverOptions());
  const Eigen::VectorXcd linear = linearResponse(scene.model, true);
  const Eigen::VectorXcd x1 = harmonic(scene.model, start, 1);
  EXPECT_LT((x1 - linear).cwiseAbs().maxCoeff(), 1e-6 * linear.cwiseAbs().maxCoeff());
  // The regime this is about: on the full system the start's residual is
  // above the static state's.
  auto full = makeHbSystem(scene.model, false);
  EXPECT_GT(test::scaledResidualNorm(*full, full->fromFullCoefficients(start)),
            10.0 * test::scaledResidualNorm(*full, full->fromFullCoefficients(operatingPoint(scene.model, *scene.at_rest))));
}

// A single solve near the peak on defaults: the own dogleg converges from
// the linear stuck response without a fallback (from the static state
// itself it stalled, |g| 12.3 -> 3.4 in 39 iterations, and the chain ended
// with Ipopt after two more stalled solves), on the orbit the continuation
// in the force reaches, its contacts pressed. Begun at zero, a solve here
// ended on a harmonic-balance solution whose contacts pulled (penalty_law
// 3.6, negative_pressure 0.23) reported as converged.
TEST(LapJoint, ADefaultSolveNearThePeakConvergesFromTheLinearisedStart) {
  constexpr double kPeak = 1534.0;
  app::SceneSettings scene;
  scene.path = test::problem("lap-joint.toml");
  scene.omega = kPeak;
  const app::Solution s = app::solve(scene, app::SolveOptions());
  ASSERT_TRUE(s.converged()) << terminationName(s.run.result.termination);
  EXPECT_EQ(s.run.start, "preload");
  EXPECT_TRUE(s.run.fallback.attempts.empty()) << describeFallbacks(s.run.fallback);
  EXPECT_EQ(s.run.result.solver, "dogleg");
  EXPECT_LE(s.run.result.iterations, 40);
  for (const LawInvariants& law : s.invariants)
    for (const auto& [name, value] : law.violations) {
      if (name == "penalty_law" || name == "negative_pressure") {
        EXPECT_LT(value, 1e-6) << "law " << law.law << " " << name;
      }
    }
  const app::Solution reference = solveLap(15.0, kPeak);
  const double x = s.summary.displacements[kForcedDof].max_abs;
  EXPECT_NEAR(x, reference.summary.displacements[kForcedDof].max_abs, 1e-6 * x);
}

// The joint's nonlinear mode about its bolted state: at small amplitude the
// stuck structure's first bending mode (the sliders' k_t in), at large
// amplitude, the pairs sliding, the sliding structure's, the damping ratio
// peaking in between (microslip).
// On its default range: the pressed interface would open on the linear mode
// at 3.4e-4 (3.3 times the slip onset), so the range ends at 3 times that,
// 1.03e-3 (about 10³ times from), instead of at 10³ times the onset (10⁵
// times from), where the joint separates and the backbone takes minutes.
TEST(LapJoint, NonlinearModeGoesFromTheStuckJointToTheSlidingOneAboutTheBoltedState) {
  app::SceneSettings scene;
  scene.path = test::problem("lap-joint.toml");
  app::ModesOptions o;
  o.points = 10;
  const app::ModesRun run = app::modes(scene, o);
  const Backbone& b = run.backbone;
  EXPECT_GE(run.options.to, 1e3 * run.options.from * (1.0 - 1e-12));  // 10 times the onset at least
  EXPECT_LT(run.options.to, 1.1e3 * run.options.from);
  ASSERT_TRUE(b.complete());
  const double stuck = firstFrequency(run.scene.model, true), sliding = firstFrequency(run.scene.model, false);
  std::printf("lap joint: linear %.8g (stuck %.8g), a = %.4g: %.8g (sliding %.8g)\n", b.start.omega, stuck,
              b.points.back().amplitude, b.points.back().omega, sliding);
  EXPECT_NEAR(b.start.omega, stuck, 1e-9 * stuck);
  EXPECT_NEAR(b.points.front().omega, stuck, 1e-6 * stuck);
  EXPECT_NEAR(b.points.back().omega, sliding, 2e-3 * sliding);
  EXPECT_GT(stuck - sliding, 0.02 * stuck);  // the check above tells the two apart
  double peak = 0.0;
  for (const BackbonePoint& p : b.points) peak = std::max(peak, p.damping_ratio);
  EXPECT_GT(peak, 3.0 * b.points.front().damping_ratio);
  EXPECT_GT(peak, 1.2 * b.points.back().damping_ratio);
}

}  // namespace
}  // namespace eqhb
