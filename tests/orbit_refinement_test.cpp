#include "eqhb/orbits/orbit_refinement.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/continuation/coarse_start.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

using orbits::RefinementOptions;
using orbits::refineByShooting;



// Root mean square over one period and every DOF of x_series − x_orbit, on
// 3001 instants (not the projection's): the L2 distance of a series to the orbit.
double l2Distance(const HbModel& model, const orbits::ShootingResult& orbit, const Eigen::VectorXd& full) {
  const auto flow = orbits::makeFlow(model, 0.0);
  orbits::FlowSamples at;
  const int count = 3001;
  for (int s = 0; s < count; ++s) at.times.push_back(orbit.start_time + flow->period() * s / count);
  EXPECT_TRUE(flow->integrate(orbit.state, orbit.start_time, flow->period(), false, &at).ok);
  double sum = 0.0;
  const int n = model.structure.dofs();
  for (int s = 0; s < count; ++s) {
    const Eigen::VectorXd y = orbits::harmonicState(model, full, at.times[s]);
    for (int i = 0; i < n; ++i) sum += std::pow(y[i] - at.displacement(s, i), 2);
  }
  return std::sqrt(sum / (count * n));
}

TEST(OrbitRefinement, DenHartogPeakIsExactWherePlainHarmonicBalanceIsNot) {
  const double r = 1.5, beta = 0.3;
  const HbModel model = test::denHartog(r, beta, 5, 80);
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  const auto refined = refineByShooting(model, hb, RefinementOptions());
  ASSERT_TRUE(refined.converged) << refined.failure;
  const double exact = test::denHartogAmplitude(r, beta);
  EXPECT_NEAR(refined.max_abs[0] / exact, 1.0, 1e-9);
  // Plain harmonic balance at the same H is off by far more.
  const double hb_error = std::abs(peakDisplacements(model, hb)[0] / exact - 1.0);
  EXPECT_GT(hb_error, 1e-5);
  // The refined series is the L2 projection of the orbit: closer than HB,
  // and moving any coefficient away from it only increases the distance.
  const double refined_l2 = l2Distance(model, refined.orbit, refined.full);
  EXPECT_LT(refined_l2, 0.1 * l2Distance(model, refined.orbit, hb));
  for (int c : {0, 1, 2, 5}) {
    for (double delta : {-1e-4, 1e-4}) {
      Eigen::VectorXd moved = refined.full;
      moved[c] += delta;
      EXPECT_GT(l2Distance(model, refined.orbit, moved), refined_l2) << "coefficient " << c << ", " << delta;
    }
  }
}

// The Signorini equality form approaches the elastic-impact orbit as H grows
// (orbits/default_restitution.h): the default refinement shoots to that
// orbit, the harmonic balance's displacement coefficients come closer to it
// at each H, while the plastic orbit (e = 0) stays away.
TEST(OrbitRefinement, ContactHarmonicBalanceApproachesTheElasticImpactOrbit) {
  const HbModel scene = loadScene(test::problem("contact.toml")).model;
  auto distance = [&](const HbModel& model, const Eigen::VectorXd& hb, const Eigen::VectorXd& orbit) {
    const Eigen::Index x = static_cast<Eigen::Index>(model.basis.size()) * model.structure.dofs();
    return (hb.head(x) - orbit.head(x)).norm() / orbit.head(x).norm();
  };
  double previous = 1.0;
  for (int h : {5, 10, 20}) {
    const HbModel model = withHarmonics(scene, h);
    auto system = makeHbSystem(model, true);
    SolverOptions options;
    options.residual_tolerance = 1e-10;
    auto solver = makeSolver("dogleg");
    const SolverResult r = CoarseStart(model, true, options.linear_algebra).solve(*solver, *system, options, nullptr);
    ASSERT_TRUE(r.converged()) << "H = " << h;
    const Eigen::VectorXd hb = system->fullCoefficients(r.solution);
    const auto elastic = refineByShooting(model, hb, RefinementOptions());
    ASSERT_TRUE(elastic.converged) << elastic.failure;
    EXPECT_EQ(elastic.orbit.events.count("impact"), 1u);
    const double d = distance(model, hb, elastic.full);
    std::printf("contact H = %d: distance to the elastic-impact orbit %.4f\n", h, d);
    EXPECT_LT(d, 0.8 * previous) << "H = " << h;
    previous = d;
    if (h == 20) {
      RefinementOptions plastic;
      plastic.restitution = 0.0;
      const auto other = refineByShooting(model, hb, plastic);
      ASSERT_TRUE(other.converged) << other.failure;
      EXPECT_GT(distance(model, hb, other.full), 2.5 * d);
    }
  }
  EXPECT_LT(previous, 0.095);
}

TEST(OrbitRefinement, CoarseStartProjectsOnMoreHarmonics) {
  // HB at H = 5 starts shooting; the orbit projected on 40 harmonics is far
  // closer to the orbit, and its first 5 harmonics are the H = 5 projection's.
  const HbModel model = test::denHartog(1.5, 0.3, 5, 80);
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  const auto coarse = refineByShooting(model, hb, RefinementOptions());
  RefinementOptions wide;
  wide.output_harmonics = 40;
  const auto fine = refineByShooting(model, hb, wide);
  ASSERT_TRUE(coarse.converged && fine.converged);
  EXPECT_EQ(fine.basis.count(), 40);
  EXPECT_EQ(fine.full.size(), 2 * fine.basis.size());
  HbModel fine_model = model;
  fine_model.basis = fine.basis;
  fine_model.samples = 16 * 40;
  EXPECT_LT(l2Distance(fine_model, fine.orbit, fine.full), 0.01 * l2Distance(model, coarse.orbit, coarse.full));
  // (up to the aliasing of the coarse projection's 288 instants, ~288^-3)
  for (int c = 0; c < model.basis.size(); ++c) EXPECT_NEAR(fine.full[c], coarse.full[c], 1e-7) << c;
  EXPECT_NEAR(fine.max_abs[0] / test::denHartogAmplitude(1.5, 0.3), 1.0, 1e-9);
}

TEST(OrbitRefinement, ForcesFollowTheLawsSignConvention) {
  // friction-1d at ω = 0.4 (stick-slip): the refined force's first harmonic
  // agrees with harmonic balance's to its accuracy, and with a direct
  // quadrature of the orbit's force samples.
  HbModel model = loadScene(test::problem("friction-1d.toml")).model;
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  const auto refined = refineByShooting(model, hb, RefinementOptions());
  ASSERT_TRUE(refined.converged) << refined.failure;
  const int nb = model.basis.size(), n = model.structure.dofs();
  const Eigen::Vector2d refined_force(refined.full[n * nb], refined.full[n * nb + 1]);
  const Eigen::Vector2d hb_force(hb[n * nb], hb[n * nb + 1]);
  // (harmonic balance's own error on the force's first harmonic is 2 % here)
  EXPECT_LT((refined_force - hb_force).norm(), 0.05 * hb_force.norm());
  const auto flow = orbits::makeFlow(model, 0.0);
  orbits::FlowSamples at;
  const int count = 20000;
  for (int s = 0; s < count; ++s) at.times.push_back(refined.orbit.start_time + flow->period() * s / count);
  ASSERT_TRUE(flow->integrate(refined.orbit.state, refined.orbit.start_time, flow->period(), false, &at).ok);
  Eigen::Vector2d quadrature = Eigen::Vector2d::Zero();
  for (int s = 0; s < count; ++s)
    quadrature += 2.0 / count * at.force(s, 0) *
                  Eigen::Vector2d(std::cos(model.omega * at.times[s]), std::sin(model.omega * at.times[s]));
  EXPECT_LT((refined_force - quadrature).norm(), 1e-3 * quadrature.norm());
  // And the stick-slip orbit is much closer to its projection than to HB.
  EXPECT_LT(l2Distance(model, refined.orbit, refined.full), 0.1 * l2Distance(model, refined.orbit, hb));
}

TEST(OrbitRefinement, RefusesWhatItCannotRefine) {
  const HbModel model = test::denHartog(1.5, 0.3, 5, 80);
  const Eigen::VectorXd hb = test::harmonicBalance(model);
  RefinementOptions few;
  few.samples = 5;  // k_max = 9 needs 19
  EXPECT_THROW(refineByShooting(model, hb, few), InputError);
  RefinementOptions negative;
  negative.output_harmonics = -1;
  EXPECT_THROW(refineByShooting(model, hb, negative), InputError);
  RefinementOptions bounce;
  bounce.restitution = 1.5;
  EXPECT_THROW(refineByShooting(model, hb, bounce), InputError);
  HbModel shared = model;
  shared.laws.push_back(shared.laws[0]);
  EXPECT_THROW(refineByShooting(shared, Eigen::VectorXd::Zero(3 * model.basis.size()), RefinementOptions()),
               InputError);
  const Scene joint = loadScene(test::problem("contact-friction-2d.toml"));  // no exact flow for it
  EXPECT_THROW(refineByShooting(joint.model, Eigen::VectorXd::Zero(200), RefinementOptions()),
               InputError);
}

}  // namespace
}  // namespace eqhb
