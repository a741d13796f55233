// The basic laws' zero sets and special values (the conformance checks of
// every registered law are in law_registry_test.cpp).
#include <gtest/gtest.h>

#include <random>

#include "eqhb/laws/coulomb_2d.h"
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/laws/stribeck.h"
#include "eqhb/laws/joints/jenkins.h"
#include "law_checks.h"
#include "test_support.h"

namespace eqhb {
namespace {

TEST(Laws, ExactFormsVanishOnTheirGraphs) {
  // 2D Coulomb: sticking (v = 0, ‖r‖ <= μN), sliding r = −μN v/‖v‖.
  for (auto form : {Coulomb2DForm::kMax, Coulomb2DForm::kProjection}) {
    Coulomb2D law(2.0, form, 0.6);
    LawSamples s;
    s.resize(3, 2);
    s.force.row(0) << 1.0, -1.2;                                      // stick
    s.velocity.row(1) << 3.0, 4.0;                                     // slide
    s.force.row(1) << -2.0 * 0.6, -2.0 * 0.8;
    s.velocity.row(2) << 1.0, 0.0;                                     // wrong force
    s.force.row(2) << 2.0, 0.0;
    law.evaluate(s, false);
    EXPECT_LT(s.psi.topRows(2).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_GT(s.psi.row(2).norm(), 1e-3);
  }
  // Signorini: g p = 0 with g, p >= 0, for every form; not when both > 0 or one < 0.
  for (auto form : {SignoriniForm::kMin, SignoriniForm::kFischerBurmeister, SignoriniForm::kSignSquare}) {
    Signorini law(1.0, form, 2.0);
    LawSamples s;
    s.resize(4, 1);
    s.displacement(0, 0) = 0.3;  // open gap, no pressure
    s.displacement(1, 0) = 1.0;  // closed gap, pressure
    s.force(1, 0) = 5.0;
    s.displacement(2, 0) = 0.5;  // open gap with pressure: wrong
    s.force(2, 0) = 1.0;
    s.displacement(3, 0) = 1.5;  // penetration: wrong
    law.evaluate(s, false);
    EXPECT_LT(s.psi.topRows(2).cwiseAbs().maxCoeff(), 1e-14) << signoriniFormName(form);
    EXPECT_GT(std::abs(s.psi(2, 0)), 1e-3) << signoriniFormName(form);
    EXPECT_GT(std::abs(s.psi(3, 0)), 1e-3) << signoriniFormName(form);
  }
  // Stribeck: sliding force is −L(v) sign(v), sticking within L(0).
  Stribeck stribeck(1.0, 1.5, 0.5);
  LawSamples s;
  s.resize(3, 1);
  s.velocity(0, 0) = 0.7;
  s.force(0, 0) = -stribeck.limit(0.7);
  s.force(1, 0) = 1.4;  // stick below μs N
  s.velocity(2, 0) = -0.2;
  s.force(2, 0) = 1.0;  // too small a force while sliding
  stribeck.evaluate(s, false);
  EXPECT_LT(s.psi.topRows(2).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_GT(std::abs(s.psi(2, 0)), 1e-3);
}

// A Stribeck step slides with the limit at the step's θ-velocity
// (θ u_end + (1 − θ) v_start), sticks within L(0), and reverses inside the
// step with the mean force at L(0).
TEST(Laws, StribeckStepTakesTheLimitAtTheThetaVelocity) {
  const Stribeck law(1.0, 1.5, 0.5);
  const double h = 0.01;
  StepProblem step;
  step.h = h;
  step.delassus = LocalMatrix::Constant(1, 1, h);
  step.x_start = LocalVector::Zero(1);
  step.force_start = LocalVector::Zero(1);
  for (double theta : {0.5, 1.0})
    for (double v0 : {0.3, -0.3, 0.0})
      for (double a : {-6.0, 4.0}) {  // beyond L(0): slides
        if (v0 * a < 0.0 && std::abs(v0) < (std::abs(a) + 1.5) * h) continue;  // would reverse
        step.theta = theta;
        step.v_start = LocalVector::Constant(1, v0);
        step.u_free = LocalVector::Constant(1, v0 + a * h);
        const double lambda = law.solveStep(step)[0], end = v0 + a * h + h * lambda;
        const double mid = theta * end + (1.0 - theta) * v0;
        EXPECT_NEAR(lambda, -std::copysign(law.limit(mid), end), 1e-13) << theta << " " << v0 << " " << a;
      }
  step.theta = 0.5;
  step.v_start = LocalVector::Constant(1, 0.0);
  step.u_free = LocalVector::Constant(1, 1.2 * h);  // within L(0) = 1.5: sticks
  EXPECT_NEAR(law.solveStep(step)[0], -1.2, 1e-14);
  // Reversal: from v0 = 0.004 under a free acceleration −4, zero after
  // 0.004 / 5.5 and slides back at −2.5 for the rest of the step.
  step.v_start = LocalVector::Constant(1, 0.004);
  step.u_free = LocalVector::Constant(1, 0.004 - 4.0 * h);
  const double lambda = law.solveStep(step)[0], t_zero = 0.004 / 5.5;
  EXPECT_NEAR(0.004 - 4.0 * h + h * lambda, -2.5 * (h - t_zero), 1e-15);
}

TEST(Laws, NonPhysicalParametersAreRejected) {
  EXPECT_THROW(Coulomb2D(-1.0, Coulomb2DForm::kMax), InputError);
  EXPECT_THROW(Signorini(std::nan(""), SignoriniForm::kMin), InputError);
  EXPECT_THROW(Signorini(1.0, SignoriniForm::kMin, -1.0), InputError);
  EXPECT_THROW(Stribeck(-1.0, 1.0, 0.5), InputError);
  EXPECT_THROW(Stribeck(1.0, 0.5, 0.5), InputError);  // static below dynamic
  EXPECT_THROW(Stribeck(1.0, 1.5, 0.0), InputError);
  EXPECT_THROW(CubicStiffness{std::numeric_limits<double>::infinity()}, InputError);
}

}  // namespace
}  // namespace eqhb
