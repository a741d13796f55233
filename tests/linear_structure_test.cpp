// The order of the structure's matrices: LinearStructure::fromMassStiffnessDamping
// and every reader that builds a structure put K and C where their names say.
// C and K are both n x n, so a swap compiles and runs: only the response
// tells, and a stiffness-only structure answers in phase, a damping-only one
// with a sine part.
#include "eqhb/structures/linear_structure.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "eqhb/scenes/scene.h"

namespace eqhb {
namespace {

// The first harmonic's coefficients [a; b] of x under the load cos ωt on DOF 0.
Eigen::VectorXd responseToCosine(const LinearStructure& s, double omega) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * s.dofs());
  f[0] = 1.0;
  return s.harmonicOperator(1, omega).lu().solve(f);
}

TEST(LinearStructure, StiffnessAloneAnswersInPhaseAndDampingAloneDoesNot) {
  const Eigen::MatrixXd m = Eigen::MatrixXd::Identity(1, 1);
  const Eigen::MatrixXd k = Eigen::MatrixXd::Constant(1, 1, 4.0);
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(1, 1);
  const Eigen::MatrixXd c = Eigen::MatrixXd::Constant(1, 1, 0.5);
  // At ω = 1: (k − ω²m) a = 1 with k = 4; with k = 0, c = 0.5:
  // [−1, 0.5; −0.5, −1] [a; b] = [1; 0], a = −0.8, b = 0.4.
  for (const bool sparse : {false, true}) {
    SCOPED_TRACE(sparse ? "sparse" : "dense");
    const LinearStructure stiff =
        sparse ? LinearStructure::fromMassStiffnessDamping(SparseMatrix(m.sparseView()), SparseMatrix(k.sparseView()),
                                                           SparseMatrix(zero.sparseView()))
               : LinearStructure::fromMassStiffnessDamping(m, k, zero);
    const LinearStructure damped =
        sparse ? LinearStructure::fromMassStiffnessDamping(
                     SparseMatrix(m.sparseView()), SparseMatrix(zero.sparseView()), SparseMatrix(c.sparseView()))
               : LinearStructure::fromMassStiffnessDamping(m, zero, c);
    const Eigen::VectorXd in_phase = responseToCosine(stiff, 1.0);
    EXPECT_NEAR(in_phase[0], 1.0 / 3.0, 1e-15);
    EXPECT_EQ(in_phase[1], 0.0);
    const Eigen::VectorXd lagging = responseToCosine(damped, 1.0);
    EXPECT_NEAR(lagging[0], -0.8, 1e-15);
    EXPECT_NEAR(lagging[1], 0.4, 1e-15);
    EXPECT_EQ(Eigen::MatrixXd(stiff.stiffness)(0, 0), 4.0);
    EXPECT_EQ(stiff.damping.nonZeros(), 0);
    EXPECT_EQ(Eigen::MatrixXd(damped.damping)(0, 0), 0.5);
    EXPECT_EQ(damped.stiffness.nonZeros(), 0);
  }
}

const char* kScene = R"(
name = "t"
[structure]
%s
[[forcing]]
dof = 1
cos = 1.0
[harmonic_balance]
harmonics = 1
samples = 16
omega = 1.0
)";

Scene sceneWithStructure(const std::string& structure) {
  std::string text = kScene;
  text.replace(text.find("%s"), 2, structure);
  return parseScene(text, "t.toml");
}

TEST(LinearStructure, TheScenesMatricesLandInTheirNamedPlaces) {
  const Scene inline_matrices =
      sceneWithStructure("type = \"matrices\"\nmass = [[1.0]]\ndamping = [[0.5]]\nstiffness = [[4.0]]\n");
  EXPECT_EQ(Eigen::MatrixXd(inline_matrices.model.structure.stiffness)(0, 0), 4.0);
  EXPECT_EQ(Eigen::MatrixXd(inline_matrices.model.structure.damping)(0, 0), 0.5);
  EXPECT_EQ(Eigen::MatrixXd(inline_matrices.model.structure.mass)(0, 0), 1.0);
  // A chain: K = k T and C = d T with the same pattern T.
  const Scene chain = sceneWithStructure("type = \"chain\"\ndofs = 2\nm = 1.0\nk = 3.0\nd = 0.1\n");
  const Eigen::MatrixXd stiffness = chain.model.structure.stiffness, damping = chain.model.structure.damping;
  EXPECT_EQ(stiffness(0, 0), 3.0 * 2.0);
  EXPECT_NEAR((damping - (0.1 / 3.0) * stiffness).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace eqhb
