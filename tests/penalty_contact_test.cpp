// The penalty unilateral spring (laws/penalty_contact.h), beyond the
// conformance checks every registered law passes (law_registry_test.cpp):
// a wall always pressed is a linear spring, a wall never touched is no law,
// the harmonic-balance solution of its scene agrees with the time reference
// (which steps the law through solveStep, not through Ψ) better as H grows.
#include <gtest/gtest.h>

#include <map>

#include "eqhb/backends/registry.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/invariants.h"
#include "eqhb/laws/penalty_contact.h"
#include "eqhb/references/time_integrator.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

using Solved = test::SolvedScene;

// On the condensed system, from rest.
Solved solve(const std::string& file, const std::vector<std::string>& set = {}) {
  return test::solveFromRest(file, set);
}

// The coefficients of x on every DOF (the first n · basis rows of `full`).
Eigen::VectorXd displacements(const Solved& s) {
  return s.full.head(s.model.structure.dofs() * s.model.basis.size());
}

// The harmonic balance of the linear structure alone: A_k x_k = f_k per harmonic.
Eigen::VectorXd linearResponse(const HbModel& model) {
  const int n = model.structure.dofs(), nb = model.basis.size();
  const Eigen::VectorXd f = forcingCoefficients(model);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n * nb);
  const auto& ks = model.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int w = ks[h] == 0 ? 1 : 2, o = model.basis.offset(static_cast<int>(h));
    Eigen::VectorXd rhs(w * n);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < w; ++r) rhs[r * n + i] = f[i * nb + o + r];
    const Eigen::VectorXd y = model.structure.harmonicOperator(ks[h], model.omega).fullPivLu().solve(rhs);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < w; ++r) x[i * nb + o + r] = y[r * n + i];
  }
  return x;
}

// With the wall far below the motion (g0 = −50, always pressed) the law is
// the linear spring p = k_n (x − g0): the structure with k_n added on DOF 2
// and a static load k_n g0 there, whose harmonic balance is exact.
TEST(PenaltyContact, AlwaysPressedIsALinearSpring) {
  const double k_n = 10.0, g0 = -50.0;
  const Solved s = solve("penalty-contact.toml", {"law.gap=" + std::to_string(g0)});
  ASSERT_TRUE(s.result.converged()) << s.result.summary();
  HbModel linear = s.model;
  Eigen::MatrixXd k = Eigen::MatrixXd(linear.structure.stiffness);
  k(1, 1) += k_n;
  linear.structure = LinearStructure::fromMassStiffnessDamping(Eigen::MatrixXd(linear.structure.mass), k,
                                                               Eigen::MatrixXd(linear.structure.damping));
  linear.structure.loads = s.model.structure.loads;
  linear.structure.loads.push_back({1, 0, k_n * g0, 0.0});
  const Eigen::VectorXd expected = linearResponse(linear);
  const Eigen::VectorXd got = displacements(s);
  EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
}

// With the wall above the motion (g0 = 50) nothing touches it: the free chain.
TEST(PenaltyContact, NeverTouchedIsNoLaw) {
  const Solved s = solve("penalty-contact.toml", {"law.gap=50"});
  ASSERT_TRUE(s.result.converged()) << s.result.summary();
  const Eigen::VectorXd expected = linearResponse(s.model);
  const Eigen::VectorXd got = displacements(s);
  EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
  EXPECT_LT(s.full.tail(s.model.basis.size()).cwiseAbs().maxCoeff(), 1e-12);  // no pressure
}

// L2 error of the displacements against the time reference (θ-method on the
// law's solveStep, started from the HB solution), at H = 5 and 20; the law's
// own checks on the truncated series fall with H too.
TEST(PenaltyContact, ErrorAgainstTheTimeReferenceFallsWithH) {
  std::vector<double> errors;
  std::vector<std::map<std::string, double>> checks;
  for (int h : {5, 20}) {
    const Solved s = solve("penalty-contact.toml", {"harmonic_balance.harmonics=" + std::to_string(h)});
    ASSERT_TRUE(s.result.converged()) << "H = " << h << ": " << s.result.summary();
    checks.emplace_back();
    const auto reports = checkInvariants(s.model, s.full);
    for (const auto& [name, value] : reports[0].violations) checks.back()[name] = value;
    TimeOptions options;
    options.step = 1e-3;
    options.periodic_tolerance = 1e-8;
    const TimeReference ref = integrateToSteadyState(s.model, options, s.full);
    ASSERT_TRUE(ref.periodic);
    double error = 0.0;
    for (const auto& e : compareWithReference(s.model, s.full, ref))
      if (e.label[0] == 'x') error = std::max(error, e.relative_l2);
    errors.push_back(error);
  }
  EXPECT_LT(errors[1], 0.3 * errors[0]);
  EXPECT_LT(errors[1], 2e-3);
  for (const char* name : {"penalty_law", "negative_pressure"}) {
    EXPECT_LT(checks[1].at(name), 0.5 * checks[0].at(name)) << name;
    EXPECT_LT(checks[1].at(name), 0.2) << name;
  }
}

}  // namespace
}  // namespace eqhb
