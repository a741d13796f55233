#include "eqhb/laws/coulomb_1d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "eqhb/error.h"

namespace eqhb {
namespace {

LawSamples samplesOf(const std::vector<double>& v, const std::vector<double>& r) {
  LawSamples s;
  s.resize(static_cast<int>(v.size()), 1);
  for (size_t i = 0; i < v.size(); ++i) {
    s.velocity(i, 0) = v[i];
    s.force(i, 0) = r[i];
  }
  return s;
}

// One time step of a unit mass under a constant free acceleration a (no
// friction) from v0 = ±speed, as Law::solveStep sees it: D = h, u_free =
// v0 + a h. The end velocity v0 + a h + h λ must be the exact one of the
// contact under Coulomb's law.
double exactEndVelocity(double v0, double a, double h, double mu_n) {
  const double s = v0 > 0.0 ? 1.0 : -1.0;
  const double slowing = a - s * mu_n;  // acceleration while sliding the old way
  const double t_zero = slowing * s < 0.0 ? -v0 / slowing : h + 1.0;
  if (t_zero >= h) return v0 + slowing * h;  // no zero within the step
  if (std::abs(a) <= mu_n) return 0.0;       // stops and sticks
  return (a + s * mu_n) * (h - t_zero);      // reverses: slides the other way
}

TEST(Coulomb1D, AStepHoldsTheExactImpulseWhenTheVelocityReverses) {
  const double mu_n = 0.3, h = 0.01;
  const Coulomb1D law(mu_n, CoulombForm::kMinMax);
  StepProblem step;
  step.h = h;
  step.theta = 0.5;
  step.delassus = LocalMatrix::Constant(1, 1, h);
  step.x_start = LocalVector::Zero(1);
  step.force_start = LocalVector::Zero(1);
  int reversals = 0;
  for (double sign : {1.0, -1.0})
    for (double speed : {1e-4, 2e-3, 5e-3, 9e-3, 0.05})
      for (double a : {-2.0, -0.8, -0.5, -0.31, -0.2, 0.0, 0.25, 0.6, 1.5}) {
        const double v0 = sign * speed, accel = sign * a;
        step.v_start = LocalVector::Constant(1, v0);
        step.u_free = LocalVector::Constant(1, v0 + accel * h);
        const double lambda = law.solveStep(step)[0];
        EXPECT_LE(std::abs(lambda), mu_n * (1.0 + 1e-15));
        const double end = v0 + accel * h + h * lambda, exact = exactEndVelocity(v0, accel, h, mu_n);
        EXPECT_NEAR(end, exact, 1e-15) << "v0 = " << v0 << ", a = " << accel;
        if (exact * v0 < 0.0) ++reversals;
      }
  EXPECT_GE(reversals, 10);  // the cases include reversals inside the step
  // From rest the step sticks or slips as before: λ = proj(−u_free / D).
  step.v_start = LocalVector::Zero(1);
  step.u_free = LocalVector::Constant(1, 0.5 * h);
  EXPECT_DOUBLE_EQ(law.solveStep(step)[0], -0.3);
  step.u_free = LocalVector::Constant(1, -0.1 * h);
  EXPECT_DOUBLE_EQ(law.solveStep(step)[0], 0.1);
}

const CoulombForm kAllForms[] = {CoulombForm::kMinMax, CoulombForm::kProjection,
                                 CoulombForm::kTanh, CoulombForm::kPiecewise};

TEST(Coulomb1D, ExactFormsVanishExactlyOnTheCoulombGraph) {
  for (CoulombForm form : {CoulombForm::kMinMax, CoulombForm::kProjection}) {
    Coulomb1D law(2.0, form, 0.7);
    // sticking (v = 0, |r| <= μN), sliding (r = −μN sign v)
    LawSamples on = samplesOf({0.0, 0.0, 0.0, 1.5, -0.3}, {-2.0, 0.3, 2.0, -2.0, 2.0});
    law.evaluate(on, false);
    EXPECT_LT(on.psi.cwiseAbs().maxCoeff(), 1e-15) << coulombFormName(form);
    // off the graph: sliding with the wrong force, sticking beyond the limit
    LawSamples off = samplesOf({1.0, -1.0, 0.0, 0.5}, {2.0, 0.0, 2.5, -1.0});
    law.evaluate(off, false);
    EXPECT_GT(off.psi.cwiseAbs().minCoeff(), 1e-3) << coulombFormName(form);
  }
}

TEST(Coulomb1D, WeakDerivativesMatchFiniteDifferencesAwayFromKinks) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  const double h = 1e-7;
  for (CoulombForm form : kAllForms) {
    Coulomb1D law(1.3, form, 0.8, 3.0);
    std::vector<double> v, r;
    for (int i = 0; i < 400; ++i) {
      v.push_back(u(rng));
      r.push_back(u(rng));
    }
    LawSamples s = samplesOf(v, r);
    law.evaluate(s, true);
    for (size_t i = 0; i < v.size(); ++i) {
      LawSamples vp = samplesOf({v[i] + h, v[i] - h}, {r[i], r[i]});
      LawSamples rp = samplesOf({v[i], v[i]}, {r[i] + h, r[i] - h});
      law.evaluate(vp, false);
      law.evaluate(rp, false);
      const double dv = (vp.psi(0, 0) - vp.psi(1, 0)) / (2 * h);
      const double dr = (rp.psi(0, 0) - rp.psi(1, 0)) / (2 * h);
      EXPECT_NEAR(s.dpsi_dvelocity(i, 0), dv, 1e-5) << coulombFormName(form) << " v=" << v[i];
      EXPECT_NEAR(s.dpsi_dforce(i, 0), dr, 1e-5) << coulombFormName(form) << " r=" << r[i];
    }
  }
}

TEST(Coulomb1D, TiesTakeTheConstantBranch) {
  // a = ρ(r+μN) − v = 0 exactly: the min branch counts as inactive.
  Coulomb1D law(1.0, CoulombForm::kMinMax, 1.0);
  LawSamples s = samplesOf({0.0}, {-1.0});
  law.evaluate(s, true);
  EXPECT_EQ(s.dpsi_dvelocity(0, 0), 1.0);
  EXPECT_EQ(s.dpsi_dforce(0, 0), 0.0);
}

TEST(Coulomb1D, RejectsNonPhysicalParameters) {
  EXPECT_THROW(Coulomb1D(-0.1, CoulombForm::kMinMax), InputError);
  EXPECT_THROW(Coulomb1D(1.0, CoulombForm::kMinMax, 0.0), InputError);
  EXPECT_THROW(Coulomb1D(std::nan(""), CoulombForm::kMinMax), InputError);
  EXPECT_THROW(Coulomb1D(1.0, CoulombForm::kTanh, 1.0, -2.0), InputError);
  EXPECT_THROW(parseCoulombForm("signum"), InputError);
}

}  // namespace
}  // namespace eqhb
