#include "eqhb/structures/beam.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "eqhb/error.h"
#include "eqhb/scenes/scene.h"
#include "check_support.h"

namespace eqhb {
namespace {

TEST(Beam, ClosedFormRootsAreTheTabulatedBetaL) {
  BeamParameters unit;  // E I / (ρA L⁴) = 1: ω_n = (β_n L)²
  const auto w = cantileverFrequencies(unit, 4);
  const double beta_l[] = {1.87510407, 4.69409113, 7.85475744, 10.99554073};
  for (int r = 0; r < 4; ++r) EXPECT_NEAR(std::sqrt(w[r]), beta_l[r], 1e-8);
}

TEST(Beam, FiniteElementFrequenciesConvergeToTheCantileverFromAbove) {
  BeamParameters beam{40, 2.1e11, 8.3e-9, 0.785, 0.6};
  const StructureMatrices s = cantileverBeam(beam);
  ASSERT_EQ(s.dofs(), 80);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes{Eigen::MatrixXd(s.stiffness), Eigen::MatrixXd(s.mass)};
  const auto exact = cantileverFrequencies(beam, 5);
  for (int r = 0; r < 5; ++r) {
    const double fe = std::sqrt(modes.eigenvalues()[r]);
    EXPECT_GE(fe, exact[r] * (1 - 1e-12)) << "mode " << r + 1;  // consistent mass: an upper bound
    EXPECT_LT(fe / exact[r] - 1, 2e-5) << "mode " << r + 1;
  }
  // Hermite cubics: the frequency error falls as h⁴ (halving h divides it by ~16).
  auto error = [&](int elements, int mode) {
    BeamParameters b = beam;
    b.elements = elements;
    const StructureMatrices c = cantileverBeam(b);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> m{Eigen::MatrixXd(c.stiffness), Eigen::MatrixXd(c.mass)};
    return std::sqrt(m.eigenvalues()[mode]) / exact[mode] - 1;
  };
  const double ratio = error(10, 2) / error(20, 2);
  EXPECT_GT(ratio, 13.0);
  EXPECT_LT(ratio, 17.0);
}

TEST(Beam, TotalMassAndTipStiffnessAreThoseOfTheBeam) {
  BeamParameters beam{10, 3.0, 2.0, 1.5, 2.0};
  const StructureMatrices s = cantileverBeam(beam);
  // A rigid unit translation of the free nodes + clamp would carry ρA L; the
  // clamped model's tip static deflection under a unit load is L³ / (3 E I).
  Eigen::VectorXd f = Eigen::VectorXd::Zero(s.dofs());
  f[beamTransverseDof(10)] = 1.0;
  Eigen::MatrixXd k(s.stiffness);
  const Eigen::VectorXd x = k.ldlt().solve(f);
  EXPECT_NEAR(x[beamTransverseDof(10)], 8.0 / (3 * 3.0 * 2.0), 1e-12);
  // Unit transverse displacement field w = 1 (θ = 0) at the free nodes.
  Eigen::VectorXd w = Eigen::VectorXd::Zero(s.dofs());
  for (int node = 1; node <= 10; ++node) w[beamTransverseDof(node)] = 1.0;
  // wᵀ M w = ρA L minus the clamped node's share of the first element.
  EXPECT_LT(w.dot(Eigen::MatrixXd(s.mass) * w), 1.5 * 2.0);
  EXPECT_GT(w.dot(Eigen::MatrixXd(s.mass) * w), 1.5 * 2.0 * 0.9);
}

TEST(Beam, SceneAttachesLawsAndLoadsToNodes) {
  const char* text = R"(
name = "b"
[structure]
type = "beam"
elements = 8
E = 1.0
I = 1.0
rhoA = 1.0
L = 1.0
rayleigh = [0.0, 1e-4]
[[forcing]]
node = 8
cos = 1.0
[[law]]
type = "coulomb-1d"
nodes = [5]
muN = 0.1
[harmonic_balance]
harmonics = 3
samples = 64
omega = 3.0
)";
  const Scene s = parseScene(text, "b.toml");
  EXPECT_EQ(s.model.structure.dofs(), 16);
  EXPECT_EQ(s.model.laws[0].attachment.dofs(), std::vector<int>{8});
  EXPECT_EQ(s.model.structure.loads[0].dof, 14);
  test::expectSceneError(test::replaced(text, "nodes = [5]", "nodes = [9]"),
                         "law[0].nodes = 9: no such node (the structure has 8", {}, "b.toml");
  test::expectSceneError(test::replaced(text, "E = 1.0", "E = -1.0"), "structure.E = -1", {}, "b.toml");
}

}  // namespace
}  // namespace eqhb

namespace eqhb {
namespace {

TEST(Beam, ShippedBeamScenesHaveTheirSizesAndSitNearTheFirstMode) {
  const Scene damper = loadScene(test::problem("beam-damper.toml"));
  EXPECT_GE(damper.model.structure.dofs(), 100);
  EXPECT_GE(damper.model.laws.size(), 5u);
  const Scene joint = loadScene(test::problem("beam-joint-large.toml"));
  EXPECT_GE(joint.model.structure.dofs(), 2000);
  EXPECT_GE(joint.model.laws.size(), 50u);
  for (const Scene* s : {&damper, &joint}) {
    // Both scenes put ω near 1.8751² sqrt(E I / (ρA L⁴)) = 3.516.
    const double omega_1 = cantileverFrequencies(BeamParameters{}, 1)[0];
    EXPECT_NEAR(s->model.omega / omega_1, 1.0, 0.1) << s->name;
    for (const auto& law : s->model.laws) EXPECT_EQ(law.attachment.dof(0) % 2, 0) << "transverse DOF";
  }
}

}  // namespace
}  // namespace eqhb
