// The hot path allocates nothing: residual and weak-Jacobian evaluations of
// every law, on both systems, after construction. Global operator new is
// replaced in this test binary to count heap allocations.
#include <gtest/gtest.h>

#include <atomic>

#include <optional>

#include "eqhb/laws/coulomb_2d.h"
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/laws/joints/contact_friction.h"
#include "eqhb/laws/joints/jenkins.h"
#include "eqhb/laws/joints/jenkins_aft.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/laws/stribeck.h"
#include "eqhb/modes/linear_modes.h"
#include "eqhb/modes/mode_system.h"
#include "observed_new.h"
#include "test_support.h"

namespace {
std::atomic<long> allocations{0};
}

void observeAllocation(std::size_t) { ++allocations; }

namespace eqhb {
namespace {

std::shared_ptr<Law> contactFriction(int tangential, NormalForm normal, std::optional<double> k_t) {
  const FrictionForm friction = tangential == 1 ? FrictionForm::kMinMax : FrictionForm::kProjection;
  return std::make_shared<ContactFriction>(test::contactFrictionParameters(tangential, normal, friction, k_t));
}

// Every law on the last DOFs of a 3-DOF chain, both systems; the dense
// Jacobian and the sparse one (fixed pattern) after the first evaluation.
TEST(Allocation, ResidualAndJacobianAllocateNothing) {
  const std::vector<std::shared_ptr<Law>> laws = {
      std::make_shared<Coulomb1D>(7.2, CoulombForm::kMinMax),
      std::make_shared<Coulomb2D>(8.0, Coulomb2DForm::kMax),
      std::make_shared<Signorini>(2.0, SignoriniForm::kFischerBurmeister),
      std::make_shared<Stribeck>(1.0, 1.5, 0.5),
      std::make_shared<CubicStiffness>(0.5),
      std::make_shared<Jenkins>(1, 1.2, 2.0, FrictionForm::kMinMax),
      std::make_shared<Jenkins>(2, 1.2, 2.0, FrictionForm::kProjection),
      std::make_shared<JenkinsAft>(std::vector<JenkinsAft::Slider>{{1.2, 2.0}}),
      contactFriction(1, NormalForm::kMin, std::nullopt),
      contactFriction(2, NormalForm::kFischerBurmeister, 2.5),
      contactFriction(1, NormalForm::kCompliant, std::nullopt)};
  for (const auto& law : laws)
    for (bool condensed : {true, false}) {
      HbModel model = test::chainWithFriction(7.2, CoulombForm::kMinMax, 10, 0.4, 512, HarmonicKind::kAll);
      Eigen::MatrixXd t = 2.0 * Eigen::MatrixXd::Identity(3, 3);
      t(0, 1) = t(1, 0) = t(1, 2) = t(2, 1) = -1.0;
      t(2, 2) = 1.0;
      model.structure = LinearStructure::fromMassStiffnessDamping(Eigen::MatrixXd::Identity(3, 3), t, 0.02 * t);
      model.structure.loads.push_back({0, 1, 20.0, 0.0});
      std::vector<int> dofs;
      for (int a = 0; a < law->dimension(); ++a) dofs.push_back(3 - law->dimension() + a);
      model.laws = {{dofs, law}};
      const std::string label = law->type() + " on " + std::to_string(dofs.size()) + " DOFs" +
                                (condensed ? ", condensed" : ", full");
      const long at_start = allocations.load();
      auto system = makeHbSystem(model, condensed);
      ASSERT_GT(allocations.load(), at_start) << "the counter must see the construction's buffers";
      const Eigen::VectorXd z = Eigen::VectorXd::Constant(system->size(), 0.3);
      Eigen::VectorXd g(system->size());
      Eigen::MatrixXd j(system->size(), system->size());
      SparseMatrix sparse = system->jacobianPattern();
      system->residualAndJacobian(z, g, j);  // warm-up
      system->residualAndSparseJacobian(z, g, sparse);
      const long before = allocations.load();
      for (int i = 0; i < 3; ++i) {
        system->residual(z, g);
        system->residualAndJacobian(z, g, j);
      }
      EXPECT_EQ(allocations.load() - before, 0) << label << ", dense Jacobian";
      const long before_sparse = allocations.load();
      for (int i = 0; i < 3; ++i) system->residualAndSparseJacobian(z, g, sparse);
      EXPECT_EQ(allocations.load() - before_sparse, 0) << label << ", sparse Jacobian";
    }
}

// The nonlinear mode's systems, full and condensed, at a new ω and ξ each
// call (the condensed one then factors every A_k again, in its own buffers).
TEST(Allocation, ModeSystemsAllocateNothingAtANewOmegaAndXi) {
  HbModel model = test::chainWithFriction(7.2, CoulombForm::kMinMax, 10, 0.4, 128, HarmonicKind::kAll);
  model.laws.push_back({{0}, std::make_shared<CubicStiffness>(0.5)});
  const Eigen::VectorXd shape = linearModes(model)[0].shape;
  for (bool condensed : {true, false}) {
    auto system = makeModeSystem(model, shape, false, condensed);
    system->setAmplitude(3.0);
    Eigen::VectorXd z = Eigen::VectorXd::Constant(system->size(), 0.3);
    z[system->omegaIndex()] = 1.2;
    z[system->xiIndex()] = 0.05;
    Eigen::VectorXd g(system->size()), column(system->size());
    Eigen::MatrixXd j(system->size(), system->size());
    system->residualAndJacobian(z, g, j);  // warm-up
    const long before = allocations.load();
    for (int i = 1; i <= 3; ++i) {
      z[system->omegaIndex()] += 0.01;
      z[system->xiIndex()] += 0.001;
      system->residual(z, g);
      system->residualAndJacobian(z, g, j);
      system->amplitudeDerivative(column);
    }
    EXPECT_EQ(allocations.load() - before, 0) << (condensed ? "condensed" : "full");
  }
}

}  // namespace
}  // namespace eqhb
