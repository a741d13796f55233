#include "eqhb/harmonic_balance/hb_systems.h"

#include <gtest/gtest.h>

#include <complex>
#include <string>

#include "eqhb/error.h"
#include "eqhb/backends/registry.h"
#include "test_support.h"

namespace eqhb {
namespace {

using test::chainWithFriction;
using test::finiteDifferenceJacobian;

class JacobianTest : public ::testing::TestWithParam<std::tuple<CoulombForm, bool>> {};

TEST_P(JacobianTest, WeakJacobianMatchesFiniteDifferences) {
  const auto [form, condensed] = GetParam();
  // All harmonics (constant term included) to exercise every Gram entry.
  for (HarmonicKind kind : {HarmonicKind::kOdd, HarmonicKind::kAll}) {
    HbModel model = chainWithFriction(3.0, form, 4, 0.45, 128, kind);
    std::unique_ptr<HbSystem> system;
    if (condensed) system = std::make_unique<CondensedSystem>(model);
    else system = std::make_unique<FullSystem>(model);
    srand(11);
    const Eigen::VectorXd z = 2.0 * Eigen::VectorXd::Random(system->size());
    Eigen::VectorXd g(system->size());
    Eigen::MatrixXd j(system->size(), system->size());
    ASSERT_TRUE(system->residualAndJacobian(z, g, j));
    const Eigen::MatrixXd fd = finiteDifferenceJacobian(*system, z);
    EXPECT_LT((j - fd).cwiseAbs().maxCoeff(), 1e-5 * (1.0 + fd.cwiseAbs().maxCoeff()))
        << coulombFormName(form) << (condensed ? " condensed" : " full");
    Eigen::VectorXd g_only(system->size());
    ASSERT_TRUE(system->residual(z, g_only));
    EXPECT_EQ((g - g_only).norm(), 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    FormsAndSystems, JacobianTest,
    ::testing::Combine(::testing::Values(CoulombForm::kMinMax, CoulombForm::kProjection,
                                         CoulombForm::kTanh, CoulombForm::kPiecewise),
                       ::testing::Bool()));

// x = Re(X e^{iωt}) with (K − ω²M + iωC) X = F: independent of the real
// block assembly under test.
Eigen::VectorXcd exactLinearResponse(const HbModel& model) {
  const std::complex<double> i(0.0, 1.0);
  const double w = model.omega;
  Eigen::MatrixXcd a = model.structure.stiffness.cast<std::complex<double>>() -
                       w * w * model.structure.mass.cast<std::complex<double>>() +
                       i * w * model.structure.damping.cast<std::complex<double>>();
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(2);
  f[0] = 20.0;
  return a.lu().solve(f);
}

TEST(HbSystems, WithoutFrictionBothSystemsGiveTheExactLinearResponse) {
  for (bool condensed : {false, true}) {
    HbModel model = chainWithFriction(0.0, CoulombForm::kMinMax, 5, 0.55);
    std::unique_ptr<HbSystem> system;
    if (condensed) system = std::make_unique<CondensedSystem>(model);
    else system = std::make_unique<FullSystem>(model);
    auto solver = makeSolver("dogleg-newton");
    SolverOptions options;
    options.residual_tolerance = 1e-12;
    const SolverResult result =
        solver->solve(*system, Eigen::VectorXd::Zero(system->size()), options);
    ASSERT_TRUE(result.converged()) << result.summary();
    const Eigen::VectorXd full = system->fullCoefficients(result.solution);
    const Eigen::VectorXcd x = exactLinearResponse(model);
    const int nb = model.basis.size();
    for (int dof = 0; dof < 2; ++dof) {
      EXPECT_NEAR(full[dof * nb + 0], x[dof].real(), 1e-10);   // cos ωt
      EXPECT_NEAR(full[dof * nb + 1], -x[dof].imag(), 1e-10);  // sin ωt
      EXPECT_LT(full.segment(dof * nb + 2, nb - 2).norm(), 1e-10);  // no higher harmonics
    }
    EXPECT_LT(full.tail(nb).norm(), 1e-10);  // r = 0
  }
}

TEST(HbSystems, CondensationReproducesTheFullResidualOnTheLinearManifold) {
  HbModel model = chainWithFriction(2.0, CoulombForm::kMinMax, 6, 0.3);
  FullSystem full(model);
  CondensedSystem condensed(model);
  srand(3);
  const Eigen::VectorXd lambda = Eigen::VectorXd::Random(condensed.size());
  const Eigen::VectorXd z = condensed.fullCoefficients(lambda);
  Eigen::VectorXd g_full(full.size()), g_condensed(condensed.size());
  ASSERT_TRUE(full.residual(z, g_full));
  ASSERT_TRUE(condensed.residual(lambda, g_condensed));
  const int dynamic = 2 * model.basis.size();
  EXPECT_LT(g_full.head(dynamic).norm(), 1e-11);  // dynamics exactly satisfied
  EXPECT_LT((g_full.tail(condensed.size()) - g_condensed).norm(), 1e-11);
  EXPECT_LT((condensed.fromFullCoefficients(z) - lambda).norm(), 0.0 + 1e-15);
}

TEST(HbSystems, SingularDynamicStiffnessIsReportedForTheCondensedSystem) {
  HbModel model = chainWithFriction(1.0, CoulombForm::kMinMax, 3, 0.5);
  model.structure.damping.setZero();
  // Undamped chain at its first natural frequency: A_1 is singular.
  model.omega = std::sqrt((3.0 - std::sqrt(5.0)) / 2.0);
  EXPECT_THROW(CondensedSystem{model}, std::runtime_error);
  EXPECT_NO_THROW(FullSystem{model});
}

// The physics check behind every solver's verdict (SquareSystem::violatedPhysics):
// at the converged answer the friction force dissipates what its limit demands;
// no force at all (1) or a force driving the slip (2) is refused, named, on both
// systems, while the Gibbs ringing of a truncated answer is not.
TEST(HbSystems, AFrictionForceThatDissipatesTooLittleIsNamed) {
  for (bool condensed : {true, false}) {
    const HbModel model = chainWithFriction(3.0, CoulombForm::kMinMax, 7, 0.45);
    std::unique_ptr<HbSystem> system;
    if (condensed) system = std::make_unique<CondensedSystem>(model);
    else system = std::make_unique<FullSystem>(model);
    const SolverResult r = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
    ASSERT_TRUE(r.converged()) << r.summary();
    EXPECT_EQ(system->violatedPhysics(r.solution), "") << "the answer itself";
    Eigen::VectorXd full = system->fullCoefficients(r.solution);
    const int forces = model.structure.dofs() * model.basis.size();
    for (double factor : {0.0, -1.0}) {
      Eigen::VectorXd wrong = full;
      wrong.tail(wrong.size() - forces) *= factor;
      const std::string why = system->violatedPhysics(system->fromFullCoefficients(wrong));
      const std::string named = "law[0] (coulomb-1d) dissipates too little: dissipation_deficit = ";
      ASSERT_EQ(why.rfind(named, 0), 0u) << (condensed ? "condensed" : "full") << " factor " << factor << ": " << why;
      const double deficit = std::stod(why.substr(named.size()));
      if (factor == 0.0) EXPECT_EQ(deficit, 1.0) << why;  // nothing dissipated
      else EXPECT_GT(deficit, 1.5) << why;                  // energy put in, not taken out
    }
  }
}

TEST(HbSystems, InvalidModelsAreRejectedWithTheField) {
  HbModel model = chainWithFriction(1.0, CoulombForm::kMinMax, 3, 0.5);
  model.laws[0].attachment = LawAttachment({5});
  try {
    FullSystem system(model);
    FAIL() << "accepted a law on a missing DOF";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("law[0].dofs = 6"), std::string::npos) << e.what();
  }
  model = chainWithFriction(1.0, CoulombForm::kMinMax, 3, 0.5);
  model.structure.mass.coeffRef(0, 0) = -1.0;
  EXPECT_THROW(FullSystem{model}, InputError);
  model = chainWithFriction(1.0, CoulombForm::kMinMax, 3, 0.5);
  model.omega = std::nan("");
  EXPECT_THROW(FullSystem{model}, InputError);
  model = chainWithFriction(1.0, CoulombForm::kMinMax, 3, 0.5);
  model.structure.loads[0].harmonic = 2;  // not odd
  EXPECT_THROW(CondensedSystem{model}, InputError);
}

}  // namespace
}  // namespace eqhb
