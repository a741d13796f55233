// Every law: pointwise weak derivatives and assembled Jacobians (full and
// condensed) against finite differences away from kinks; zero sets.
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

struct LawCase {
  std::string label;
  std::shared_ptr<Law> law;
};

std::vector<LawCase> allLaws() {
  return {
      {"coulomb1d-minmax", std::make_shared<Coulomb1D>(1.3, CoulombForm::kMinMax, 0.8)},
      {"coulomb1d-projection", std::make_shared<Coulomb1D>(1.3, CoulombForm::kProjection, 0.8)},
      {"coulomb2d-max", std::make_shared<Coulomb2D>(1.5, Coulomb2DForm::kMax, 0.7)},
      {"coulomb2d-projection", std::make_shared<Coulomb2D>(1.5, Coulomb2DForm::kProjection, 0.7)},
      {"coulomb2d-smoothed", std::make_shared<Coulomb2D>(1.5, Coulomb2DForm::kSmoothed, 0.7, 0.3)},
      {"coulomb2d-tanh", std::make_shared<Coulomb2D>(1.5, Coulomb2DForm::kTanh, 0.7, 1e-4, 2.0)},
      {"signorini-min", std::make_shared<Signorini>(0.4, SignoriniForm::kMin, 1.5)},
      {"signorini-fb", std::make_shared<Signorini>(0.4, SignoriniForm::kFischerBurmeister, 1.5)},
      {"signorini-signsquare", std::make_shared<Signorini>(0.4, SignoriniForm::kSignSquare, 1.5)},
      {"stribeck", std::make_shared<Stribeck>(1.0, 1.5, 0.5, 0.9)},
      {"cubic", std::make_shared<CubicStiffness>(0.7)},
  };
}

class LawTest : public ::testing::TestWithParam<LawCase> {};

TEST_P(LawTest, PointwisePartialsMatchFiniteDifferences) {
  test::expectPointwisePartialsMatch(*GetParam().law, GetParam().label, 3, 300);
}

TEST_P(LawTest, AssembledJacobiansMatchFiniteDifferences) {
  test::expectAssembledJacobiansMatch(GetParam().law, GetParam().label, 17);
}

// Half-wave sampling of the assembly relies on it (Law::oddSymmetric): a law
// that claims to be odd gives −Ψ and the same partials for negated inputs,
// bit for bit, also on its kinks (v = 0, λ = ±μN, the trial force on the
// limit) where a one-sided comparison would break the symmetry.
TEST(LawSymmetry, OddLawsAreOddBitForBit) {
  std::vector<LawCase> laws = allLaws();
  laws.push_back({"coulomb1d-tanh", std::make_shared<Coulomb1D>(1.3, CoulombForm::kTanh, 0.8, 7.0)});
  laws.push_back({"coulomb1d-piecewise", std::make_shared<Coulomb1D>(1.3, CoulombForm::kPiecewise, 0.8, 7.0)});
  laws.push_back({"jenkins1-minmax", std::make_shared<Jenkins>(1, 1.2, 2.0, FrictionForm::kMinMax, 0.9)});
  laws.push_back({"jenkins2-max", std::make_shared<Jenkins>(2, 1.2, 2.0, FrictionForm::kMax, 0.9)});
  const double edges[] = {0.0, 1.3, -1.3, 1.5, -1.5, 1.2, 0.8, 1.04, 0.5, 1.0};
  int odd = 0;
  for (const LawCase& c : laws) {
    if (!c.law->oddSymmetric()) continue;
    ++odd;
    const int d = c.law->dimension(), n = 400;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    std::uniform_int_distribution<int> pick(0, 9);
    LawSamples s, m;
    s.resize(n, d);
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < d; ++a) {  // half the samples on kink values
        auto draw = [&] { return i % 2 ? u(rng) : edges[pick(rng)]; };
        s.displacement(i, a) = draw();
        s.velocity(i, a) = draw();
        s.force(i, a) = draw();
        s.force_rate(i, a) = draw();
      }
    m = s;
    m.displacement = -s.displacement;
    m.velocity = -s.velocity;
    m.force = -s.force;
    m.force_rate = -s.force_rate;
    c.law->evaluate(s, true);
    c.law->evaluate(m, true);
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < d; ++a) {
        ASSERT_EQ(m.psi(i, a), -s.psi(i, a)) << c.label << " sample " << i;
        for (int b = 0; b < d; ++b) {
          const int ab = a * d + b;
          if (c.law->usesDisplacement()) ASSERT_EQ(m.dpsi_ddisplacement(i, ab), s.dpsi_ddisplacement(i, ab)) << c.label;
          if (c.law->usesVelocity()) ASSERT_EQ(m.dpsi_dvelocity(i, ab), s.dpsi_dvelocity(i, ab)) << c.label;
          ASSERT_EQ(m.dpsi_dforce(i, ab), s.dpsi_dforce(i, ab)) << c.label << " sample " << i;
          if (c.law->usesForceRate()) ASSERT_EQ(m.dpsi_dforce_rate(i, ab), s.dpsi_dforce_rate(i, ab)) << c.label;
        }
      }
  }
  EXPECT_GE(odd, 10);  // Coulomb 1D/2D in every form, Stribeck, cubic, Jenkins
}

INSTANTIATE_TEST_SUITE_P(AllLaws, LawTest, ::testing::ValuesIn(allLaws()),
                         [](const auto& info) {
                           std::string name = info.param.label;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

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
