#include "eqhb/orbits/shooting.h"

#include <gtest/gtest.h>

#include <complex>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/laws/coulomb_2d.h"
#include "eqhb/laws/stribeck.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/references/time_integrator.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/backends/registry.h"
#include "test_support.h"

namespace eqhb {
namespace {

using orbits::PiecewiseLinearFlow;
using orbits::ShootingOptions;
using orbits::shootPeriodicOrbit;



// r = 0.6, β = 0.3: the Coulomb oscillator scene without its damping
// (X = 1.5356018; with c = 0.05 the orbit's max|x| is 1.5036029).
TEST(Shooting, DenHartogNonStopAmplitude) {
  for (const auto& [r, beta] : {std::pair{1.5, 0.3}, std::pair{0.8, 0.3}, std::pair{2.5, 0.5}, std::pair{0.6, 0.3}}) {
    const HbModel model = test::denHartog(r, beta, 5, 64);
    const PiecewiseLinearFlow flow(model, 0.0);
    Eigen::VectorXd start(2);
    start << 1.0 / (1.0 - r * r), 0.0;  // frictionless response at t = 0
    const auto orbit = shootPeriodicOrbit(flow, start, 0.0, ShootingOptions());
    ASSERT_TRUE(orbit.converged) << orbit.failure;
    const double exact = test::denHartogAmplitude(r, beta);
    EXPECT_NEAR(orbit.max_abs[0] / exact, 1.0, 1e-9) << "r = " << r;
    // Non-stop: two reversals per period, no stick.
    EXPECT_EQ(orbit.events.count("stick"), 0u);
    EXPECT_EQ(orbit.events.at("reversal"), 2);
  }
}

// The chain of the scenes without any law, or with a friction limit of 0.
HbModel linearChain(bool with_zero_friction) {
  HbModel model = test::chainWithFriction(0.0, CoulombForm::kMinMax, 1, 0.5);
  if (!with_zero_friction) model.laws.clear();
  return model;
}

// Den Hartog's oscillator's exact flow and a start far from its orbit.
struct FarFromTheOrbit {
  const HbModel model = test::denHartog(1.5, 0.3, 5, 64);
  const PiecewiseLinearFlow flow{model, 0.0};
  const Eigen::VectorXd start = Eigen::Vector2d(40.0, 3.0);
};

TEST(Shooting, AnUnconvergedOrbitHasNoMultipliers) {
  // One Newton step from far away: not an orbit, so Φ's eigenvalues mean nothing.
  const FarFromTheOrbit far;
  ShootingOptions options;
  options.max_iterations = 1;
  const auto orbit = shootPeriodicOrbit(far.flow, far.start, 0.0, options);
  ASSERT_FALSE(orbit.converged);
  EXPECT_EQ(orbit.multipliers.size(), 0);
  EXPECT_FALSE(orbit.stable);
  EXPECT_EQ(orbit.monodromy.rows(), 2);  // the last iterate's Φ is still there
}

TEST(Shooting, ATimeLimitStopsNewtonAndSaysSo) {
  const FarFromTheOrbit far;
  ShootingOptions options;
  options.time_limit = 1e-9;  // passed after the first period map
  int reports = 0;
  options.progress = [&](int iterations, int evaluations, double) {
    EXPECT_EQ(evaluations, reports + 1);
    EXPECT_EQ(iterations, 0);
    ++reports;
  };
  const auto orbit = shootPeriodicOrbit(far.flow, far.start, 0.0, options);
  EXPECT_FALSE(orbit.converged);
  EXPECT_EQ(orbit.iterations, 0);
  EXPECT_EQ(orbit.flow_evaluations, 1);
  EXPECT_EQ(reports, 1);
  EXPECT_NE(orbit.failure.find("time limit reached after 0 Newton steps and 1 period-map evaluations"), std::string::npos)
      << orbit.failure;
  EXPECT_EQ(orbit.multipliers.size(), 0);
  options.time_limit = -1.0;
  EXPECT_THROW(shootPeriodicOrbit(far.flow, far.start, 0.0, options), InputError);
}

TEST(Shooting, LinearOrbitIsTheExactResponseAndMultipliersAreExpLambdaT) {
  for (bool zero_friction : {false, true}) {
    const HbModel model = linearChain(zero_friction);
    const PiecewiseLinearFlow flow(model, 0.0);
    const auto orbit = shootPeriodicOrbit(flow, Eigen::VectorXd::Zero(4), 0.3, ShootingOptions());
    ASSERT_TRUE(orbit.converged) << orbit.failure;
    // Exact response x = Re(X e^{iωt}), (K − ω²M + iωC) X = F.
    const std::complex<double> i(0.0, 1.0);
    const double w = model.omega;
    const Eigen::MatrixXcd a = model.structure.stiffness.cast<std::complex<double>>() -
                               w * w * model.structure.mass.cast<std::complex<double>>() +
                               i * w * model.structure.damping.cast<std::complex<double>>();
    Eigen::VectorXcd f = Eigen::VectorXcd::Zero(2);
    f[0] = 20.0;
    const Eigen::VectorXcd x = a.lu().solve(f);
    orbits::FlowSamples samples;
    for (int s = 0; s < 50; ++s) samples.times.push_back(0.3 + flow.period() * s / 50.0);
    const auto run = flow.integrate(orbit.state, 0.3, flow.period(), false, &samples);
    ASSERT_TRUE(run.ok);
    double worst = 0.0, scale = 0.0;
    for (int s = 0; s < 50; ++s)
      for (int d = 0; d < 2; ++d) {
        const std::complex<double> e = std::exp(i * w * samples.times[s]);
        const double exact = (x[d] * e).real(), rate = (i * w * x[d] * e).real();
        worst = std::max({worst, std::abs(samples.displacement(s, d) - exact), std::abs(samples.velocity(s, d) - rate)});
        scale = std::max(scale, std::abs(exact));
      }
    EXPECT_LT(worst / scale, 1e-12) << "zero friction law: " << zero_friction;
    EXPECT_NEAR(orbit.max_abs[1] / std::abs(x[1]), 1.0, 1e-12);
    // Multipliers exp(λ_i T), λ_i the eigenvalues of the first-order system.
    Eigen::MatrixXd state = Eigen::MatrixXd::Zero(4, 4);
    state.topRightCorner(2, 2).setIdentity();
    state.bottomLeftCorner(2, 2) = -Eigen::MatrixXd(model.structure.stiffness);
    state.bottomRightCorner(2, 2) = -Eigen::MatrixXd(model.structure.damping);
    Eigen::VectorXcd expected = (state.eigenvalues() * flow.period()).array().exp();
    std::sort(expected.data(), expected.data() + 4, [](auto p, auto q) { return std::abs(p) > std::abs(q); });
    for (int k = 0; k < 4; ++k) {
      // Conjugate pairs: compare modulus and |arg|.
      EXPECT_NEAR(std::abs(orbit.multipliers[k]), std::abs(expected[k]), 1e-12);
      EXPECT_NEAR(std::abs(std::arg(orbit.multipliers[k])), std::abs(std::arg(expected[k])), 1e-10);
    }
    EXPECT_TRUE(orbit.stable);
  }
}

// Central differences of the flow map over [t0, t0 + duration] from y0, each
// coordinate stepped by relative_step · max(1, |y0|); the event sequence
// checked to be `events` on both sides.
Eigen::MatrixXd finiteDifferenceFlowMap(const orbits::Flow& flow, const Eigen::VectorXd& y0, double t0,
                                        double duration, double relative_step,
                                        const std::map<std::string, int>& events) {
  Eigen::MatrixXd fd(y0.size(), y0.size());
  for (int c = 0; c < y0.size(); ++c) {
    const double h = relative_step * std::max(1.0, std::abs(y0[c]));
    Eigen::VectorXd plus = y0, minus = y0;
    plus[c] += h;
    minus[c] -= h;
    const auto p = flow.integrate(plus, t0, duration, false), m = flow.integrate(minus, t0, duration, false);
    EXPECT_TRUE(p.ok && m.ok);
    EXPECT_EQ(p.events, events);
    EXPECT_EQ(m.events, events);
    fd.col(c) = (p.end - m.end) / (2 * h);
  }
  return fd;
}

TEST(Shooting, PeriodMapJacobianMatchesFiniteDifferences) {
  for (double omega : {0.4, 0.55, 0.308}) {
    HbModel model = loadScene(test::problem("friction-1d.toml")).model;
    model.omega = omega;
    const PiecewiseLinearFlow flow(model, 0.0);
    const Eigen::VectorXd hb = test::harmonicBalance(model);
    const double t0 = orbits::quietStartTime(model, hb);
    const Eigen::VectorXd y0 = orbits::harmonicState(model, hb, t0);
    const auto exact = flow.integrate(y0, t0, flow.period(), true);
    ASSERT_TRUE(exact.ok) << exact.failure;
    EXPECT_GT(exact.events.size(), 0u);
    // The same event sequence on both sides: away from a switch.
    const Eigen::MatrixXd fd = finiteDifferenceFlowMap(flow, y0, t0, flow.period(), 1e-6, exact.events);
    EXPECT_LT((fd - exact.jacobian).norm(), 1e-6 * std::max(1.0, exact.jacobian.norm())) << "omega " << omega;
  }
}

TEST(Shooting, FrictionChainFromHarmonicBalanceConvergesNearIt) {
  const HbModel model = loadScene(test::problem("friction-1d.toml")).model;
  const PiecewiseLinearFlow flow(model, 0.0);
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  const double t0 = orbits::quietStartTime(model, hb);
  const auto orbit = shootPeriodicOrbit(flow, orbits::harmonicState(model, hb, t0), t0, ShootingOptions());
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  EXPECT_LE(orbit.period_residual, 1e-11);
  EXPECT_LE(orbit.iterations, 12);
  // A periodic orbit: integrating once more returns to the start.
  const auto again = flow.integrate(orbit.state, t0, flow.period(), false);
  EXPECT_LT((again.end - orbit.state).cwiseAbs().maxCoeff(), 1e-10 * orbit.state.cwiseAbs().maxCoeff());
  // Harmonic balance with H = 10 odd harmonics is within a few per cent of it.
  const auto summary = orbits::harmonicState(model, hb, t0);
  EXPECT_NEAR(summary[1], orbit.state[1], 0.05 * orbit.max_abs[1]);
  EXPECT_TRUE(orbit.stable);
}

// Central differences of the period map from y0 at t0, with the event
// sequence checked to be `events` on both sides.
Eigen::MatrixXd finiteDifferenceMonodromy(const orbits::Flow& flow, const Eigen::VectorXd& y0, double t0,
                                          const std::map<std::string, int>& events) {
  return finiteDifferenceFlowMap(flow, y0, t0, flow.period(), 1e-6, events);
}

TEST(Shooting, ContactOrbitsWithRestitutionZeroAndOne) {
  const HbModel model = loadScene(test::problem("contact.toml")).model;
  const double gap = 2.0;
  Eigen::VectorXd start(4);
  start << 0.5, 1.0, 0.0, 0.0;
  for (double e : {0.0, 1.0}) {
    const PiecewiseLinearFlow flow(model, e);
    const auto orbit = shootPeriodicOrbit(flow, start, 0.0, ShootingOptions());
    ASSERT_TRUE(orbit.converged) << "e = " << e << ": " << orbit.failure;
    EXPECT_GE(orbit.events.at("impact"), 1);
    // Never through the wall, and on it at the impact.
    orbits::FlowSamples samples;
    for (int s = 0; s < 400; ++s) samples.times.push_back(flow.period() * s / 400.0);
    const auto run = flow.integrate(orbit.state, 0.0, flow.period(), true, &samples);
    ASSERT_TRUE(run.ok);
    EXPECT_LE(samples.displacement.col(1).maxCoeff(), gap + 1e-12);
    EXPECT_GE(samples.force.col(0).minCoeff(), 0.0);  // pressure >= 0
    // Monodromy with the impact saltation against finite differences.
    const Eigen::MatrixXd fd = finiteDifferenceMonodromy(flow, orbit.state, 0.0, run.events);
    EXPECT_LT((fd - run.jacobian).norm(), 1e-5 * std::max(1.0, run.jacobian.norm())) << "e = " << e;
    if (e == 1.0) {
      // Elastic impacts: the T-periodic orbit of the contact scene is unstable.
      EXPECT_FALSE(orbit.stable);
      EXPECT_GT(orbit.spectral_radius, 1.0);
    } else {
      EXPECT_TRUE(orbit.stable);
    }
  }
}

// The distance of the Moreau–Jean time reference, started from `hb`, to the
// exact orbit at each count of steps per period.
std::vector<double> timeReferenceDistances(const HbModel& model, const orbits::Flow& flow,
                                           const orbits::ShootingResult& orbit, const Eigen::VectorXd& hb,
                                           const std::vector<int>& steps_per_period) {
  std::vector<double> errors;
  for (int steps : steps_per_period) {
    TimeOptions options;
    options.step = flow.period() / steps;
    options.periodic_tolerance = 1e-11;
    const TimeReference ref = integrateToSteadyState(model, options, hb);
    EXPECT_TRUE(ref.periodic);
    errors.push_back(orbits::distanceToOrbit(flow, orbit, ref.displacement));
  }
  return errors;
}

// An elastic wall (penalty-contact) in closed form: the undamped, unforced
// oscillator (m = k = 1) with the wall (k_n = 10) at x = 0, started at the
// wall moving into it with speed V, is the bilinear oscillator: half a
// period pressed (stiffness 11, out to V/sqrt(11) after pi/(2 sqrt(11))),
// half open (out to -V after a further pi/2 of the open half), back at
// (0, V) after pi/sqrt(11) + pi.
TEST(Shooting, PenaltyWallFreeFlightIsTheBilinearOscillator) {
  const HbModel model = loadScene(test::problem("penalty-contact.toml"),
                                  {"structure.dofs=1", "structure.d=0", "law.dofs=[1]", "law.gap=0", "forcing.cos=0"})
                            .model;
  const PiecewiseLinearFlow flow(model, 0.0);
  const double v = 0.7, pressed = M_PI / std::sqrt(11.0), open = M_PI;
  orbits::FlowSamples samples;
  samples.times = {0.5 * pressed, pressed + 0.5 * open};
  const auto run = flow.integrate(Eigen::Vector2d(0.0, v), 0.0, pressed + open, true, &samples);
  ASSERT_TRUE(run.ok) << run.failure;
  EXPECT_NEAR(samples.displacement(0, 0), v / std::sqrt(11.0), 1e-12);
  EXPECT_NEAR(samples.force(0, 0), 10.0 * v / std::sqrt(11.0), 1e-11);  // the pressure k_n x
  EXPECT_NEAR(samples.displacement(1, 0), -v, 1e-12);
  EXPECT_NEAR(samples.force(1, 0), 0.0, 1e-15);
  EXPECT_NEAR(run.end[0], 0.0, 1e-12);
  EXPECT_NEAR(run.end[1], v, 1e-12);
  EXPECT_NEAR(run.max_abs[0], v, 1e-12);
  EXPECT_EQ(run.events.at("release"), 1);
  // The Jacobian across a release and a touch (identity saltations: the
  // force is continuous there) against finite differences, from inside the
  // pressed half.
  const Eigen::Vector2d inside(samples.displacement(0, 0), 0.0);
  const auto part = flow.integrate(inside, 0.5 * pressed, pressed + open, true);
  ASSERT_TRUE(part.ok);
  EXPECT_EQ(part.events.at("touch"), 1);
  const Eigen::MatrixXd fd = finiteDifferenceFlowMap(flow, inside, 0.5 * pressed, pressed + open, 1e-6, part.events);
  EXPECT_LT((fd - part.jacobian).norm(), 1e-7 * part.jacobian.norm());
}

// The penalty-contact scene's forced orbit (ω = 0.55, the wall touched once
// per period) shot exactly, against the independent Moreau–Jean time
// reference: the wall's force is continuous, so θ = ½ stays second order
// (4.6e-3, 1.1e-3, 3.0e-4 at 500, 1000, 2000 steps per period).
TEST(Shooting, PenaltyWallOrbitAgreesWithTheTimeReference) {
  HbModel model = loadScene(test::problem("penalty-contact.toml")).model;
  model.omega = 0.55;
  const PiecewiseLinearFlow flow(model, 0.0);
  auto system = makeHbSystem(model, false);  // the full system, which the penalty wall suits
  SolverOptions solver_options;
  solver_options.residual_tolerance = 1e-10;
  const auto solved = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), solver_options);
  ASSERT_TRUE(solved.converged());
  const Eigen::VectorXd hb = system->fullCoefficients(solved.solution);
  const double t0 = orbits::quietStartTime(model, hb);
  const auto orbit = shootPeriodicOrbit(flow, orbits::harmonicState(model, hb, t0), t0, ShootingOptions());
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  EXPECT_EQ(orbit.events.at("touch"), 1);
  EXPECT_EQ(orbit.events.at("release"), 1);
  const std::vector<double> errors = timeReferenceDistances(model, flow, orbit, hb, {500, 1000, 2000});
  std::printf("penalty wall, distance of the time reference to the exact orbit: %.3g %.3g %.3g\n", errors[0],
              errors[1], errors[2]);
  EXPECT_GT(std::log2(errors[0] / errors[2]) / 2.0, 1.8);
  EXPECT_LT(errors[2], 4e-4);
  // The multipliers: stable, and the monodromy against finite differences.
  EXPECT_TRUE(orbit.stable);
  const auto run = flow.integrate(orbit.state, t0, flow.period(), true);
  ASSERT_TRUE(run.ok);
  const Eigen::MatrixXd fd = finiteDifferenceFlowMap(flow, orbit.state, t0, flow.period(), 1e-6, run.events);
  EXPECT_LT((fd - run.jacobian).norm(), 1e-5 * std::max(1.0, run.jacobian.norm()));
}

TEST(Shooting, MoreauJeanConvergesToTheExactOrbit) {
  // Stick-slip (ω = 0.4) and continuous sliding (Coulomb oscillator).
  for (const auto& [file, omega] : {std::pair{"friction-1d.toml", 0.4}, std::pair{"coulomb-oscillator.toml", 0.6}}) {
    HbModel model = loadScene(test::problem(file)).model;
    model.omega = omega;
    const PiecewiseLinearFlow flow(model, 0.0);
    const Eigen::VectorXd hb = test::harmonicBalance(model);
    const double t0 = orbits::quietStartTime(model, hb);
    const auto orbit = shootPeriodicOrbit(flow, orbits::harmonicState(model, hb, t0), t0, ShootingOptions());
    ASSERT_TRUE(orbit.converged) << orbit.failure;
    const std::vector<double> errors = timeReferenceDistances(model, flow, orbit, hb, {250, 500, 1000});
    // θ = ½ is second order on smooth phases, first order across events:
    // at least first order overall, and small at 1000 steps per period.
    EXPECT_GT(std::log2(errors[0] / errors[2]) / 2.0, 0.9) << file;
    EXPECT_LT(errors[2], 2e-4) << file;
  }
}

// Shooting a smooth scene from its harmonic balance at the scene's H.
orbits::ShootingResult shootSmooth(const HbModel& model, const orbits::Flow& flow, const Eigen::VectorXd& hb) {
  const double t0 = orbits::quietStartTime(model, hb);
  return shootPeriodicOrbit(flow, orbits::harmonicState(model, hb, t0), t0, ShootingOptions());
}

// A smooth scene's exact flow, its harmonic balance and the orbit shot from it.
struct SmoothShot {
  explicit SmoothShot(const HbModel& model)
      : flow(orbits::makeFlow(model, 0.0)), hb(test::harmonicBalance(model)), orbit(shootSmooth(model, *flow, hb)) {}
  const std::unique_ptr<orbits::Flow> flow;
  const Eigen::VectorXd hb;
  const orbits::ShootingResult orbit;
};

TEST(Shooting, CubicOrbitAgreesWithConvergedHarmonicBalance) {
  // Smooth: harmonic balance converges spectrally, so at H = 15 odd harmonics
  // it is a second exact answer for the Gauss–Legendre shooting orbit.
  HbModel model = loadScene(test::problem("cubic.toml")).model;
  model.basis = HarmonicSet(HarmonicKind::kOdd, 15);
  model.samples = 256;
  const auto& [flow, hb, orbit] = SmoothShot(model);
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  const Eigen::VectorXd y_hb = orbits::harmonicState(model, hb, orbit.start_time);
  EXPECT_LT((y_hb - orbit.state).cwiseAbs().maxCoeff(), 1e-9 * orbit.state.cwiseAbs().maxCoeff());
  const auto run = flow->integrate(orbit.state, orbit.start_time, flow->period(), true);
  const Eigen::MatrixXd fd = finiteDifferenceMonodromy(*flow, orbit.state, orbit.start_time, run.events);
  EXPECT_LT((fd - run.jacobian).norm(), 1e-6 * std::max(1.0, run.jacobian.norm()));
  EXPECT_TRUE(orbit.stable);
}

TEST(Shooting, PlanarSlidingOrbitAndItsMonodromy) {
  const HbModel model = loadScene(test::problem("friction-2d-sliding.toml")).model;
  const auto& [flow, hb, orbit] = SmoothShot(model);
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  EXPECT_LE(orbit.period_residual, 1e-11);
  const auto run = flow->integrate(orbit.state, orbit.start_time, flow->period(), true);
  const Eigen::MatrixXd fd = finiteDifferenceMonodromy(*flow, orbit.state, orbit.start_time, run.events);
  EXPECT_LT((fd - run.jacobian).norm(), 1e-6 * std::max(1.0, run.jacobian.norm()));
  // Harmonic balance (H = 10 odd) is within a few per cent of the exact orbit.
  orbits::FlowSamples samples;
  for (int s = 0; s < 200; ++s) samples.times.push_back(orbit.start_time + flow->period() * s / 200);
  ASSERT_TRUE(flow->integrate(orbit.state, orbit.start_time, flow->period(), false, &samples).ok);
  double worst = 0.0;
  for (int s = 0; s < 200; ++s)
    worst = std::max(worst, (orbits::harmonicState(model, hb, samples.times[s]).head(2) -
                             samples.displacement.row(s).transpose()).cwiseAbs().maxCoeff());
  EXPECT_LT(worst, 0.05 * orbit.max_abs.maxCoeff());
  // The sliding force has magnitude μN = 8 everywhere on the orbit.
  for (int s = 0; s < 200; ++s) EXPECT_NEAR(samples.force.row(s).norm(), 8.0, 1e-12);
}

// The largest entry of |J − J_fd| relative to the largest of |J|, where
// J_fd are central differences over [t0, t0 + duration] with the same
// events on both sides.
double jacobianMismatch(const orbits::Flow& flow, const Eigen::VectorXd& y0, double t0, double duration) {
  const auto exact = flow.integrate(y0, t0, duration, true);
  EXPECT_TRUE(exact.ok) << exact.failure;
  const Eigen::MatrixXd fd = finiteDifferenceFlowMap(flow, y0, t0, duration, 1e-5, exact.events);
  return (fd - exact.jacobian).cwiseAbs().maxCoeff() / exact.jacobian.cwiseAbs().maxCoeff();
}

TEST(Shooting, PlanarStickSlipOrbit) {
  const HbModel model = loadScene(test::problem("friction-2d.toml")).model;
  const auto& [flow, hb, orbit] = SmoothShot(model);
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  EXPECT_LE(orbit.period_residual, 1e-11);
  EXPECT_GE(orbit.events.at("stick"), 2);
  EXPECT_EQ(orbit.events.at("stick"), orbit.events.at("slip"));
  EXPECT_TRUE(orbit.stable);
  // Exact Coulomb in the plane along the orbit: the force stays in the disc
  // ‖λ‖ <= μN = 8; at rest it may be inside, while sliding it is on the
  // circle and opposite to v.
  const int count = 500;
  orbits::FlowSamples samples;
  for (int s = 0; s < count; ++s) samples.times.push_back(orbit.start_time + flow->period() * s / count);
  ASSERT_TRUE(flow->integrate(orbit.state, orbit.start_time, flow->period(), false, &samples).ok);
  int stuck = 0;
  for (int s = 0; s < count; ++s) {
    const Eigen::Vector2d force = samples.force.row(s).transpose(), v = samples.velocity.row(s).transpose();
    EXPECT_LE(force.norm(), 8.0 * (1.0 + 1e-12));
    if (v.norm() == 0.0) {
      ++stuck;
    } else {
      EXPECT_NEAR(force.norm(), 8.0, 1e-12);
      EXPECT_NEAR(force.dot(v) / v.norm(), -8.0, 1e-10);
    }
  }
  EXPECT_GT(stuck, count / 20);
  EXPECT_LT(stuck, count - count / 20);
}

TEST(Shooting, PlanarStickSlipMonodromyMatchesFiniteDifferences) {
  const HbModel model = loadScene(test::problem("friction-2d.toml")).model;
  const auto& [flow, hb, orbit] = SmoothShot(model);
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  // The monodromy (stop and release saltations) against central
  // differences, over parts of the period and the whole. The differences
  // carry ~1e-9 of noise (event location, step control), large against the
  // monodromy's entries (~4e-4, sticking forgets the past); without the
  // saltations the mismatch is of order 1.
  for (double part : {0.5, 1.0})
    EXPECT_LT(jacobianMismatch(*flow, orbit.state, orbit.start_time, part * flow->period()), 1e-4) << part;
}

// Moreau–Jean (θ = ½) converges to the exact orbit at first order at least:
// an independent check of it.
void expectMoreauJeanConverges(const HbModel& model) {
  const auto& [flow, hb, orbit] = SmoothShot(model);
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  std::vector<double> errors;
  for (int steps : {250, 1000}) {
    TimeOptions options;
    options.step = flow->period() / steps;
    options.periodic_tolerance = 1e-11;
    const TimeReference ref = integrateToSteadyState(model, options, hb);
    ASSERT_TRUE(ref.periodic);
    errors.push_back(orbits::distanceToOrbit(*flow, orbit, ref.displacement));
  }
  EXPECT_GT(std::log2(errors[0] / errors[1]) / 2.0, 0.9);
  EXPECT_LT(errors[1], 5e-3);
}

TEST(Shooting, MoreauJeanConvergesToThePlanarStickSlipOrbit) {
  expectMoreauJeanConverges(loadScene(test::problem("friction-2d.toml")).model);
}

TEST(Shooting, MoreauJeanConvergesToTheStribeckStickSlipOrbit) {
  HbModel model = loadScene(test::problem("stribeck.toml")).model;
  model.omega = 0.2;
  expectMoreauJeanConverges(model);
}

TEST(Shooting, StribeckOrbitsAndTheirMonodromy) {
  // Stick-slip (ω = 0.2) and reversals without sticking (ω = 0.4).
  for (double omega : {0.2, 0.4}) {
    HbModel model = loadScene(test::problem("stribeck.toml")).model;
    model.omega = omega;
    const auto& [flow, hb, orbit] = SmoothShot(model);
    ASSERT_TRUE(orbit.converged) << orbit.failure;
    EXPECT_LE(orbit.period_residual, 1e-11);
    EXPECT_EQ(orbit.events.count("stick"), omega == 0.2 ? 1u : 0u);
    EXPECT_LT(jacobianMismatch(*flow, orbit.state, orbit.start_time, flow->period()), 1e-6) << omega;
    // While stuck the force stays within the static limit 1.5; while
    // sliding it is −L(|v|) sgn v.
    orbits::FlowSamples samples;
    for (int s = 0; s < 500; ++s) samples.times.push_back(orbit.start_time + flow->period() * s / 500);
    ASSERT_TRUE(flow->integrate(orbit.state, orbit.start_time, flow->period(), false, &samples).ok);
    for (int s = 0; s < 500; ++s) {
      const double v = samples.velocity(s, 1), force = samples.force(s, 0);
      if (v == 0.0) EXPECT_LE(std::abs(force), 1.5 * (1.0 + 1e-12));
      else EXPECT_NEAR(force, -std::copysign(1.0 + 0.5 * std::exp(-std::abs(v) / 0.5), v), 1e-12);
    }
  }
}

TEST(Shooting, StribeckWithoutDropIsTheClosedFormCoulombOrbit) {
  // μ_s = μ_d: the smooth-phase flow with its located events must give the
  // orbit of the closed-form Coulomb 1D flow.
  for (double omega : {0.308, 0.55}) {
    HbModel coulomb = loadScene(test::problem("friction-1d.toml")).model;
    coulomb.omega = omega;
    HbModel stribeck = coulomb;
    stribeck.laws[0].law = std::make_shared<Stribeck>(7.2, 7.2, 0.5);
    const PiecewiseLinearFlow exact(coulomb, 0.0);
    const orbits::SmoothFlow smooth(stribeck);
    const Eigen::VectorXd hb = test::harmonicBalance(coulomb);
    const double t0 = orbits::quietStartTime(coulomb, hb);
    const auto a = shootPeriodicOrbit(exact, orbits::harmonicState(coulomb, hb, t0), t0, ShootingOptions());
    const auto b = shootPeriodicOrbit(smooth, orbits::harmonicState(coulomb, hb, t0), t0, ShootingOptions());
    ASSERT_TRUE(a.converged && b.converged) << a.failure << b.failure;
    EXPECT_EQ(a.events, b.events);
    EXPECT_LT((a.state - b.state).cwiseAbs().maxCoeff(), 1e-9 * a.state.cwiseAbs().maxCoeff()) << omega;
    EXPECT_LT((a.max_abs - b.max_abs).cwiseAbs().maxCoeff(), 1e-9 * a.max_abs.maxCoeff()) << omega;
    EXPECT_LT((a.monodromy - b.monodromy).cwiseAbs().maxCoeff(), 1e-7 * a.monodromy.cwiseAbs().maxCoeff()) << omega;
  }
}

TEST(Shooting, CoulombMixedWithCubicGoesWithTheSmoothPhases) {
  // friction-1d plus a cubic spring on DOF 1: with ε = 0 the smooth-phase
  // flow (Coulomb 1D taken as Stribeck without drop) gives the closed-form
  // orbit; with ε = 0.002 it still shoots, stick-slip included.
  HbModel coulomb = loadScene(test::problem("friction-1d.toml")).model;
  coulomb.omega = 0.308;
  const PiecewiseLinearFlow exact(coulomb, 0.0);
  const Eigen::VectorXd hb = test::harmonicBalance(coulomb);
  const double t0 = orbits::quietStartTime(coulomb, hb);
  const auto a = shootPeriodicOrbit(exact, orbits::harmonicState(coulomb, hb, t0), t0, ShootingOptions());
  ASSERT_TRUE(a.converged) << a.failure;
  for (double epsilon : {0.0, 0.002}) {
    HbModel mixed = coulomb;
    mixed.laws.push_back({{0}, std::make_shared<CubicStiffness>(epsilon)});
    const auto flow = orbits::makeFlow(mixed, 0.0);
    ASSERT_NE(dynamic_cast<const orbits::SmoothFlow*>(flow.get()), nullptr);
    const auto b = shootPeriodicOrbit(*flow, orbits::harmonicState(coulomb, hb, t0), t0, ShootingOptions());
    ASSERT_TRUE(b.converged) << b.failure;
    EXPECT_GE(b.events.at("stick"), 1);
    if (epsilon == 0.0) {
      EXPECT_EQ(a.events, b.events);
      EXPECT_LT((a.state - b.state).cwiseAbs().maxCoeff(), 1e-9 * a.state.cwiseAbs().maxCoeff());
    } else {
      EXPECT_GT((a.state - b.state).cwiseAbs().maxCoeff(), 1e-3 * a.state.cwiseAbs().maxCoeff());
    }
  }
  // Signorini does not mix with smooth laws.
  HbModel contact = loadScene(test::problem("contact.toml")).model;
  contact.laws.push_back({{0}, std::make_shared<CubicStiffness>(0.1)});
  EXPECT_THROW(orbits::makeFlow(contact, 0.0), InputError);
}

TEST(Shooting, NearGrazingImpactInsideOneGridIntervalIsFound) {
  // x'' + x = 0 from x = 0, v = 1: x = sin t reaches 1 at t = π/2. A wall at
  // 1 − δ is crossed only for |t − π/2| < sqrt(2δ) ≈ 0.014, far inside one
  // grid interval (0.2): both ends of that interval are clear of the wall.
  HbModel model;
  model.structure = LinearStructure::fromMassStiffnessDamping(
      Eigen::MatrixXd::Identity(1, 1), Eigen::MatrixXd::Identity(1, 1), Eigen::MatrixXd::Zero(1, 1));
  model.structure.loads.push_back({0, 1, 0.0, 0.0});
  model.basis = HarmonicSet(HarmonicKind::kAll, 1);
  model.samples = 16;
  model.omega = 0.5;
  Eigen::VectorXd start(2);
  start << 0.0, 1.0;
  for (double delta : {1e-4, 1e-8}) {
    model.laws = {{{0}, std::make_shared<Signorini>(1.0 - delta, SignoriniForm::kMin)}};
    const PiecewiseLinearFlow flow(model, 1.0);
    const auto run = flow.integrate(start, 0.0, 2.0, true);
    ASSERT_TRUE(run.ok) << run.failure;
    EXPECT_EQ(run.events.at("impact"), 1) << delta;
    EXPECT_LE(run.max_abs[0], 1.0 - delta + 1e-14) << delta;
    // Elastic bounce at t* = asin(1 − δ): x(2) = (1 − δ) cos(2 − t*) − v* sin(2 − t*),
    // v* = cos t*; t* is conditioned as 1/sqrt(2δ) near grazing.
    const double hit = std::asin(1.0 - delta), speed = std::cos(hit);
    EXPECT_NEAR(run.end[0], (1.0 - delta) * std::cos(2.0 - hit) - speed * std::sin(2.0 - hit), 1e-14 / std::sqrt(delta))
        << delta;
  }
  // A wall just beyond the amplitude is never touched.
  model.laws = {{{0}, std::make_shared<Signorini>(1.0 + 1e-9, SignoriniForm::kMin)}};
  const auto clear = PiecewiseLinearFlow(model, 1.0).integrate(start, 0.0, 2.0, false);
  ASSERT_TRUE(clear.ok);
  EXPECT_EQ(clear.events.count("impact"), 0u);
  EXPECT_NEAR(clear.end[0], std::sin(2.0), 1e-13);
}

TEST(Shooting, BriefPlanarReleaseInsideOneStepIsFound) {
  // A stuck planar mass (M = K = I) under f = (10 cos t, 0) with μN just
  // below 10: the force it needs, |10 cos t|, exceeds μN only for
  // |t − π| < sqrt(2δ), far inside one step (up to 0.2 while stuck, where
  // the field is 0 and the error control lets the steps grow).
  for (double delta : {1e-6, 1e-8, 1e-10}) {
    HbModel model;
    model.structure = LinearStructure::fromMassStiffnessDamping(
        Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Zero(2, 2));
    model.structure.loads.push_back({0, 1, 10.0, 0.0});
    model.laws.push_back({{0, 1}, std::make_shared<Coulomb2D>(10.0 * (1.0 - delta), Coulomb2DForm::kMax)});
    model.basis = HarmonicSet(HarmonicKind::kOdd, 1);
    model.samples = 16;
    model.omega = 1.0;
    const orbits::SmoothFlow flow(model);
    const auto run = flow.integrate(Eigen::VectorXd::Zero(4), 0.05, 4.0, false);
    if (delta == 1e-10) {
      // A slide whose speed would stay below 1e-14 is not integrated: said so.
      EXPECT_FALSE(run.ok);
      EXPECT_NE(run.failure.find("below round-off"), std::string::npos) << run.failure;
      continue;
    }
    ASSERT_TRUE(run.ok) << run.failure;
    EXPECT_EQ(run.events.count("slip"), 1u) << delta;
    EXPECT_EQ(run.events.count("stick"), 1u) << delta;
    // Near t = π the load 10 cos t ≈ −10 pushes it towards −x: it slipped
    // there by a little and stuck again.
    EXPECT_LT(run.end[0], 0.0) << delta;
    EXPECT_EQ(run.end[2], 0.0);
  }
}

// Elastic dry friction (Jenkins, k_t = 5): the slider position is a state.
// The orbit from harmonic balance, its monodromy against finite
// differences, and harmonic balance converging to it as H grows.
TEST(Shooting, JenkinsOrbitMonodromyAndHarmonicBalanceError) {
  const HbModel model = loadScene(test::problem("jenkins-1d.toml")).model;
  ASSERT_TRUE(PiecewiseLinearFlow::supports(model));
  const PiecewiseLinearFlow flow(model, 0.0);
  EXPECT_EQ(flow.stateSize(), 5);  // x1, x2, v1, v2, w
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  const double t0 = orbits::quietStartTime(model, hb);
  const auto orbit = shootPeriodicOrbit(flow, orbits::harmonicState(model, hb, t0), t0, ShootingOptions());
  ASSERT_TRUE(orbit.converged) << orbit.failure;
  EXPECT_LE(orbit.period_residual, 1e-11);
  EXPECT_TRUE(orbit.stable);
  EXPECT_EQ(orbit.events.at("slip"), 2);
  EXPECT_EQ(orbit.events.at("stick"), 2);
  // On the orbit the spring force stays within the limit: |k_t (x2 − w)| <= μN.
  orbits::FlowSamples samples;
  for (int s = 0; s < 256; ++s) samples.times.push_back(t0 + flow.period() * s / 256);
  const auto run = flow.integrate(orbit.state, t0, flow.period(), false, &samples);
  ASSERT_TRUE(run.ok) << run.failure;
  EXPECT_LE(samples.force.cwiseAbs().maxCoeff(), 7.2 * (1.0 + 1e-12));
  // The monodromy from a stuck instant (force well inside the limit), where
  // every perturbation keeps the event sequence, against finite differences;
  // and from the slipping start, where w is slaved to x: ∂P/∂w = 0.
  Eigen::Index stuck = 0;
  samples.force.col(0).cwiseAbs().minCoeff(&stuck);
  const double t_stuck = samples.times[stuck];
  const auto to_stuck = flow.integrate(orbit.state, t0, t_stuck - t0, false);
  ASSERT_TRUE(to_stuck.ok) << to_stuck.failure;
  EXPECT_LT(jacobianMismatch(flow, to_stuck.end, t_stuck, flow.period()), 1e-5);
  const auto from_slip = flow.integrate(orbit.state, t0, flow.period(), true);
  EXPECT_EQ(from_slip.jacobian.col(4).cwiseAbs().maxCoeff(), 0.0);
  // Harmonic balance against the exact orbit: the sup error falls with H.
  std::vector<double> errors;
  for (int h : {5, 10, 20, 40}) {
    HbModel m = loadScene(test::problem("jenkins-1d.toml"), {"harmonic_balance.harmonics=" + std::to_string(h),
                                                            "harmonic_balance.samples=" + std::to_string(32 * h)})
                    .model;
    const Eigen::VectorXd full = test::harmonicBalance(m);
    double sup = 0.0;
    for (size_t s = 0; s < samples.times.size(); ++s)
      sup = std::max(sup, (orbits::harmonicState(m, full, samples.times[s]).head(2) -
                           samples.displacement.row(s).transpose()).cwiseAbs().maxCoeff());
    errors.push_back(sup / orbit.max_abs.maxCoeff());
  }
  for (size_t i = 1; i < errors.size(); ++i) EXPECT_LT(errors[i], 0.7 * errors[i - 1]) << i;
  EXPECT_LT(errors.back(), 5e-3);
}

// k_t → ∞: the elastic orbit tends to the rigid Coulomb one of friction-1d.
TEST(Shooting, StiffJenkinsOrbitApproachesTheCoulombOrbit) {
  auto shoot = [](const HbModel& model) {
    const auto flow = orbits::makeFlow(model, 0.0);
    const Eigen::VectorXd hb = test::harmonicBalance(model);
    const double t0 = orbits::quietStartTime(model, hb);
    return shootPeriodicOrbit(*flow, orbits::harmonicState(model, hb, t0), t0, ShootingOptions());
  };
  const auto rigid = shoot(loadScene(test::problem("friction-1d.toml")).model);
  ASSERT_TRUE(rigid.converged) << rigid.failure;
  std::vector<double> distances;
  for (const char* k_t : {"1e2", "1e3"}) {
    const auto elastic = shoot(loadScene(test::problem("jenkins-1d.toml"), {std::string("law.k_t=") + k_t}).model);
    ASSERT_TRUE(elastic.converged) << k_t << ": " << elastic.failure;
    distances.push_back((elastic.max_abs - rigid.max_abs).cwiseAbs().maxCoeff() / rigid.max_abs.maxCoeff());
  }
  EXPECT_LT(distances[1], 0.3 * distances[0]);
  EXPECT_LT(distances[1], 5e-3);  // 2.3e-3 at k_t = 1e3
}

TEST(Shooting, RejectsLawsItCannotIntegrate) {
  for (const HbModel& model :
       {loadScene(test::problem("contact-friction-2d.toml")).model,
        loadScene(test::problem("friction-2d-sliding.toml"), {"law.type=\"jenkins\"", "law.k_t=5"}).model}) {
    EXPECT_FALSE(PiecewiseLinearFlow::supports(model));
    EXPECT_FALSE(orbits::SmoothFlow::supports(model));
    EXPECT_THROW(orbits::makeFlow(model, 0.0), InputError);
  }
  EXPECT_THROW(PiecewiseLinearFlow flow(linearChain(false), 1.5), InputError);
  EXPECT_THROW(orbits::makeFlow(linearChain(false), -0.1), InputError);
}

}  // namespace
}  // namespace eqhb
