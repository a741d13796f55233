#include "eqhb/laws/law_attachment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/coulomb_2d.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/references/time_integrator.h"
#include "check_support.h"

namespace eqhb {
namespace {

using test::messageOf;

TEST(LawAttachment, ADofListIsGroundedWithUnitRows) {
  const LawAttachment w({3, 1});
  EXPECT_TRUE(w.grounded());
  EXPECT_EQ(w.dimension(), 2);
  EXPECT_EQ(w.dof(0), 3);
  EXPECT_EQ(w.dof(1), 1);
  EXPECT_EQ(w.dofs(), (std::vector<int>{3, 1}));
  EXPECT_EQ(w.describe(), "[4, 2]");
  const Eigen::Vector4d x(1.0, 2.0, 3.0, 4.0);
  EXPECT_EQ(w.gather(x, 0), 4.0);
  EXPECT_EQ(w.gather(x, 1), 2.0);
}

TEST(LawAttachment, AnAxisAgainstTheGroundIsTheGroundedForm) {
  const LawAttachment axis = LawAttachment::relative({4, 5, 6}, {}, {Eigen::Vector3d(0.0, 1.0, 0.0)});
  EXPECT_TRUE(axis.grounded());
  EXPECT_EQ(axis.dof(0), 5);
  const LawAttachment pair = LawAttachment::relative({0, 1}, {2, 3}, {Eigen::Vector2d(0.6, 0.8)});
  EXPECT_FALSE(pair.grounded());
  EXPECT_EQ(pair.dofs(), (std::vector<int>{0, 1, 2, 3}));
  const Eigen::Vector4d x(1.0, 2.0, 0.5, -1.0);
  EXPECT_DOUBLE_EQ(pair.gather(x, 0), 0.6 * (1.0 - 0.5) + 0.8 * (2.0 + 1.0));
}

// Scatter is the adjoint of gather: ⟨Wᵀλ, x⟩ = ⟨λ, W x⟩ on coefficient
// vectors, and transposeDense / rowTimes are the same W.
TEST(LawAttachment, ScatterIsTheAdjointOfGather) {
  const double c = std::cos(0.3), s = std::sin(0.3);
  const LawAttachment w = LawAttachment::relative({0, 1}, {4, 5}, {Eigen::Vector2d(c, s), Eigen::Vector2d(-s, c)});
  const int n = 6, stride = 3;
  srand(5);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(n * stride);
  const Eigen::VectorXd lambda = Eigen::VectorXd::Random(stride);
  const Eigen::MatrixXd wt = w.transposeDense(n);
  for (int a = 0; a < 2; ++a) {
    Eigen::VectorXd u(stride), y = Eigen::VectorXd::Zero(n * stride);
    w.gatherCoefficients(x.data(), stride, a, u.data());
    w.scatterCoefficients(lambda.data(), stride, a, 1.0, y.data());
    EXPECT_NEAR(u.dot(lambda), y.dot(x), 1e-14);
    for (int t = 0; t < stride; ++t) {
      double expected = 0.0;
      for (int j = 0; j < n; ++j) expected += wt(j, a) * x[j * stride + t];
      EXPECT_NEAR(u[t], expected, 1e-15);
    }
    const Eigen::MatrixXd y_dense = Eigen::MatrixXd::Random(n, 3);
    EXPECT_LT((w.rowTimes(y_dense, a) - wt.col(a).transpose() * y_dense).norm(), 1e-15);
  }
}

TEST(LawAttachment, ValidationNamesTheField) {
  EXPECT_NE(messageOf([] { LawAttachment({5}).validate(3, "law[0].dofs"); })
                .find("law[0].dofs = 6: no such DOF (the structure has 3"),
            std::string::npos);
  EXPECT_NE(messageOf([] { LawAttachment({1, 1}).validate(3, "law[0].dofs"); }).find("law[0].dofs = 2: listed twice"),
            std::string::npos);
  EXPECT_NE(messageOf([] { LawAttachment({{AttachmentTerm{0, NAN}}}).validate(3, "law[2].dofs"); })
                .find("law[2].dofs = nan: a weight must be finite"),
            std::string::npos);
  // Two components of an element between nodes share DOFs: that is allowed.
  LawAttachment::relative({0, 1}, {2, 3}, {Eigen::Vector2d(1.0, 1.0), Eigen::Vector2d(1.0, -1.0)}).validate(4, "f");
}

// The 2-DOF chain with the friction between DOF 2 and a third DOF held by a
// spring 5e11 times stiffer (stiffer makes A_k too ill-conditioned to
// condense, rcond < 1e-13): the relative element is the grounded one.
TEST(LawAttachment, RelativeElementOnAStifflyGroundedNodeIsTheGroundedElement) {
  const HbModel grounded = test::chainWithFriction(3.0, CoulombForm::kMinMax, 5, 0.45, 128);
  HbModel relative = grounded;
  Eigen::MatrixXd m = Eigen::MatrixXd::Identity(3, 3), c = Eigen::MatrixXd::Zero(3, 3),
                  k = Eigen::MatrixXd::Zero(3, 3);
  m.topLeftCorner(2, 2) = grounded.structure.mass;
  c.topLeftCorner(2, 2) = grounded.structure.damping;
  k.topLeftCorner(2, 2) = grounded.structure.stiffness;
  k(2, 2) = 5e11;
  relative.structure = LinearStructure::fromMassStiffnessDamping(m, k, c);
  relative.structure.loads = grounded.structure.loads;
  relative.laws[0].attachment = LawAttachment({{AttachmentTerm{1, 1.0}, AttachmentTerm{2, -1.0}}});
  ASSERT_FALSE(relative.laws[0].attachment.grounded());
  const Eigen::VectorXd a = test::harmonicBalance(grounded), b = test::harmonicBalance(relative);
  const int nb = grounded.basis.size();
  const double scale = a.cwiseAbs().maxCoeff();
  EXPECT_LT((a.head(2 * nb) - b.head(2 * nb)).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT((a.tail(nb) - b.tail(nb)).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT(b.segment(2 * nb, nb).cwiseAbs().maxCoeff(), 1e-12 * scale);  // the held node barely moves
}

// Two nodes in space (3 DOFs each), each on anisotropic springs to the
// ground and joined by a spring, with 2D friction in the plane (t1, t2)
// between them and a load on node 1; `r` rotates the whole joint.
HbModel jointInSpace(const Eigen::Matrix3d& r, int harmonics = 3) {
  Eigen::MatrixXd rot = Eigen::MatrixXd::Zero(6, 6);
  rot.topLeftCorner(3, 3) = r;
  rot.bottomRightCorner(3, 3) = r;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(6, 6), m = Eigen::MatrixXd::Identity(6, 6);
  k.topLeftCorner(3, 3) = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
  k.bottomRightCorner(3, 3) = Eigen::Vector3d(2.0, 1.5, 4.0).asDiagonal();
  k.topRightCorner(3, 3) = -0.5 * Eigen::Matrix3d::Identity();
  k.bottomLeftCorner(3, 3) = -0.5 * Eigen::Matrix3d::Identity();
  k.topLeftCorner(3, 3) += 0.5 * Eigen::Matrix3d::Identity();
  k.bottomRightCorner(3, 3) += 0.5 * Eigen::Matrix3d::Identity();
  m(3, 3) = m(4, 4) = m(5, 5) = 1.5;
  const Eigen::MatrixXd kr = rot * k * rot.transpose(), mr = rot * m * rot.transpose();
  HbModel model;
  model.structure = LinearStructure::fromMassStiffnessDamping(mr, kr, 0.03 * kr);
  const Eigen::Vector3d load = r * Eigen::Vector3d(1.0, 0.4, 0.3);
  for (int i = 0; i < 3; ++i) model.structure.loads.push_back({i, 1, load[i], 0.0});
  const Eigen::VectorXd t1 = r * Eigen::Vector3d(1.0, 0.0, 0.0), t2 = r * Eigen::Vector3d(0.0, 1.0, 0.0);
  model.laws.push_back({LawAttachment::relative({0, 1, 2}, {3, 4, 5}, {t1, t2}),
                        std::make_shared<Coulomb2D>(0.3, Coulomb2DForm::kMax, RhoSetting(1.0))});
  model.basis = HarmonicSet(HarmonicKind::kOdd, harmonics);
  model.samples = 64;
  model.omega = 1.1;
  return model;
}

Eigen::Matrix3d someRotation() {
  return (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

// x' = R x node by node, the same friction force: to 1e-10.
TEST(LawAttachment, TheJointRotatedInSpaceGivesTheSameResponse) {
  const Eigen::Matrix3d r = someRotation();
  const HbModel axes = jointInSpace(Eigen::Matrix3d::Identity()), turned = jointInSpace(r);
  const Eigen::VectorXd a = test::harmonicBalance(axes), b = test::harmonicBalance(turned);
  const int nb = axes.basis.size();
  const double scale = a.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.1);
  EXPECT_LT(test::turnedMismatch(r, a, b, nb, 2), 1e-10 * scale);
  EXPECT_LT((a.tail(2 * nb) - b.tail(2 * nb)).cwiseAbs().maxCoeff(), 1e-10 * scale);
}

// The assembled Jacobians of a relative element (full dense and sparse,
// condensed) against central differences.
TEST(LawAttachment, RelativeElementJacobiansMatchFiniteDifferences) {
  const HbModel model = jointInSpace(someRotation(), 2);
  for (bool condensed : {false, true}) {
    std::unique_ptr<HbSystem> system = makeHbSystem(model, condensed);
    srand(3);
    const Eigen::VectorXd z = Eigen::VectorXd::Random(system->size());
    EXPECT_LT(test::jacobianError(*system, z), 1e-5) << condensed;
  }
  FullSystem full(model);
  SparseMatrix sparse = full.jacobianPattern();
  const Eigen::VectorXd z = Eigen::VectorXd::Random(full.size());
  Eigen::VectorXd g(full.size()), g_dense(full.size());
  Eigen::MatrixXd dense(full.size(), full.size());
  ASSERT_TRUE(full.residualAndSparseJacobian(z, g, sparse));
  ASSERT_TRUE(full.residualAndJacobian(z, g_dense, dense));
  EXPECT_EQ((Eigen::MatrixXd(sparse) - dense).cwiseAbs().maxCoeff(), 0.0);
}

// The time reference on the rotated joint: its λ agrees with harmonic
// balance, and with the unrotated joint's.
TEST(LawAttachment, TheTimeReferenceHandlesRelativeElements) {
  TimeOptions options;
  options.step = 2e-3;
  options.periodic_tolerance = 1e-9;
  const HbModel turned = jointInSpace(someRotation(), 15);
  const Eigen::VectorXd hb = test::harmonicBalance(turned);
  const TimeReference ref = integrateToSteadyState(turned, options, hb);
  ASSERT_TRUE(ref.periodic);
  const HbModel axes = jointInSpace(Eigen::Matrix3d::Identity(), 15);
  const TimeReference plain = integrateToSteadyState(axes, options, test::harmonicBalance(axes));
  ASSERT_TRUE(plain.periodic);
  for (const ChannelError& e : compareWithReference(turned, hb, ref))
    EXPECT_LT(e.relative_l2, 0.1) << e.label;  // stick-slip on 15 harmonics: the series rings
  EXPECT_LT((ref.force - plain.force).cwiseAbs().maxCoeff(), 1e-6 * plain.force.cwiseAbs().maxCoeff());
}

TEST(LawAttachment, ExactOrbitsRefuseARelativeElementNamingTheLaw) {
  HbModel model = jointInSpace(someRotation());
  const std::string message = messageOf([&] { orbits::makeFlow(model, 0.0); });
  EXPECT_NE(message.find("law[0].between"), std::string::npos) << message;
  EXPECT_NE(message.find("coulomb-2d law between two nodes"), std::string::npos) << message;
}

}  // namespace
}  // namespace eqhb
