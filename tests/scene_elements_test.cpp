// Elements between two nodes in scene files: `between`, `normal`,
// `tangents` and a structure's `node_table` (scenes/scene.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "eqhb/error.h"
#include "eqhb/round_trip.h"
#include "eqhb/scenes/law_rho.h"
#include "eqhb/scenes/scene.h"
#include "check_support.h"
#include "command_solve_support.h"

namespace eqhb {
namespace {

std::string matrix(const Eigen::MatrixXd& m) {
  std::string out = "[";
  for (int i = 0; i < m.rows(); ++i) {
    out += i ? ", [" : "[";
    for (int j = 0; j < m.cols(); ++j) out += (j ? ", " : "") + formatRoundTrip(m(i, j));
    out += "]";
  }
  return out + "]";
}

std::string vector(const Eigen::VectorXd& v) {
  std::string out = "[";
  for (int i = 0; i < v.size(); ++i) out += (i ? ", " : "") + formatRoundTrip(v[i]);
  return out + "]";
}

// Two nodes in space (DOFs 1-3 and 4-6) on anisotropic springs, joined by a
// spring, with contact and friction between them (normal n, tangents t1,
// t2), preloaded and forced on node 1; `r` rotates the whole joint.
std::string jointScene(const Eigen::Matrix3d& r, const std::string& extra_law_keys = "") {
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(6, 6), m = Eigen::MatrixXd::Identity(6, 6), rot = Eigen::MatrixXd::Zero(6, 6);
  k.topLeftCorner(3, 3) = Eigen::Vector3d(1.5, 2.0, 3.0).asDiagonal();
  k.bottomRightCorner(3, 3) = Eigen::Vector3d(2.0, 1.5, 4.5).asDiagonal();
  k.topRightCorner(3, 3) = -0.5 * Eigen::Matrix3d::Identity();
  k.bottomLeftCorner(3, 3) = -0.5 * Eigen::Matrix3d::Identity();
  m(3, 3) = m(4, 4) = m(5, 5) = 1.5;
  rot.topLeftCorner(3, 3) = r;
  rot.bottomRightCorner(3, 3) = r;
  const Eigen::MatrixXd kr = rot * k * rot.transpose(), mr = rot * m * rot.transpose();
  const Eigen::Vector3d load = r * Eigen::Vector3d(0.3, 1.0, 0.4);
  std::string text = "name = \"joint\"\n[structure]\ntype = \"matrices\"\nmass = " + matrix(mr) +
                     "\nstiffness = " + matrix(kr) + "\ndamping = " + matrix(0.03 * kr) +
                     "\nnode_table = [[1, 2, 3], [4, 5, 6]]\n";
  for (int i = 0; i < 3; ++i)
    text += "[[forcing]]\ndof = " + std::to_string(i + 1) + "\nharmonic = 1\ncos = " + formatRoundTrip(load[i]) + "\n";
  text += "[[law]]\ntype = \"contact-friction\"\nbetween = [1, 2]\nnormal = " + vector(r * Eigen::Vector3d(0, 0, 1)) +
          "\ntangents = [" + vector(r * Eigen::Vector3d(1, 0, 0)) + ", " + vector(r * Eigen::Vector3d(0, 1, 0)) +
          "]\nmu = 0.4\npreload = 1.0\ngap = 0.5\n" + extra_law_keys;
  text += "[harmonic_balance]\nharmonics = 3\nset = \"all\"\nsamples = 64\nomega = 1.2\n";
  return text;
}

Eigen::Matrix3d someRotation() {
  return (Eigen::AngleAxisd(0.9, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

TEST(SceneElements, BetweenReadsTheNodesAlongTheDirections) {
  const Scene scene = parseScene(jointScene(Eigen::Matrix3d::Identity()), "joint.toml");
  const LawAttachment& w = scene.model.laws[0].attachment;
  ASSERT_EQ(w.dimension(), 3);
  EXPECT_FALSE(w.grounded());
  // Row 0, the normal (0, 0, 1): z of node 1 minus z of node 2.
  ASSERT_EQ(w.row(0).size(), 2u);
  EXPECT_EQ(w.row(0)[0].dof, 2);
  EXPECT_EQ(w.row(0)[0].weight, 1.0);
  EXPECT_EQ(w.row(0)[1].dof, 5);
  EXPECT_EQ(w.row(0)[1].weight, -1.0);
  EXPECT_EQ(w.row(1)[0].dof, 0);  // t1 = x
  EXPECT_EQ(w.row(2)[0].dof, 1);  // t2 = y
}

// The joint rotated in space: x' = R x node by node and the same contact
// forces, to 1e-10.
TEST(SceneElements, TheJointRotatedInSpaceGivesTheSameResponse) {
  const Eigen::Matrix3d r = someRotation();
  const Scene axes = parseScene(jointScene(Eigen::Matrix3d::Identity()), "axes.toml");
  const Eigen::VectorXd a = test::solvedAsTheCommandSolves(jointScene(Eigen::Matrix3d::Identity()), "axes.toml"),
                        b = test::solvedAsTheCommandSolves(jointScene(r), "turned.toml");
  const int nb = axes.model.basis.size();
  const double scale = a.cwiseAbs().maxCoeff();
  EXPECT_LT(test::turnedMismatch(r, a, b, nb, 2), 1e-10 * scale);
  EXPECT_LT((a.tail(3 * nb) - b.tail(3 * nb)).cwiseAbs().maxCoeff(), 1e-10 * scale);
}

// Contact with friction between node 1 (DOFs 1, 2) and node 2 (DOFs 3, 4)
// held by springs 5e11 times stiffer than the structure: the grounded law
// dofs = [2, 1] (normal y, tangent x), up to the held node's own motion
// (|λ| / 5e11, about 6e-13 here, which the solution cannot resolve better).
TEST(SceneElements, AnElementOnAStifflyHeldNodeIsTheGroundedElement) {
  const std::string common =
      "[[forcing]]\ndof = 1\nharmonic = 1\ncos = 1.0\n[[forcing]]\ndof = 2\nharmonic = 1\ncos = 0.3\n"
      "[harmonic_balance]\nharmonics = 5\nset = \"all\"\nsamples = 64\nomega = 0.8\n";
  const std::string law = "[[law]]\ntype = \"contact-friction\"\nmu = 0.3\npreload = 0.5\ngap = 0.2\n";
  const std::string grounded =
      "name = \"c\"\n[structure]\ntype = \"matrices\"\nmass = [[1.0, 0.0], [0.0, 1.0]]\n"
      "stiffness = [[2.0, 0.3], [0.3, 1.0]]\ndamping = [[0.04, 0.0], [0.0, 0.02]]\n" +
      law + "dofs = [2, 1]\n" + common;
  const std::string relative =
      "name = \"c\"\n[structure]\ntype = \"matrices\"\nmass = [[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]]\n"
      "stiffness = [[2.0, 0.3, 0, 0], [0.3, 1.0, 0, 0], [0, 0, 5e11, 0], [0, 0, 0, 5e11]]\n"
      "damping = [[0.04, 0, 0, 0], [0, 0.02, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]]\n"
      "node_table = [[1, 2], [3, 4]]\n" +
      law + "between = [1, 2]\nnormal = [0.0, 1.0]\ntangents = [[1.0, 0.0]]\n" + common;
  const Eigen::VectorXd a = test::solvedAsTheCommandSolves(grounded, "grounded.toml"),
                        b = test::solvedAsTheCommandSolves(relative, "relative.toml");
  const int nb = parseScene(grounded, "grounded.toml").model.basis.size();
  ASSERT_EQ(b.size(), a.size() + 2 * nb);
  // The held node moves by the contact force over its spring, no more.
  const double force = a.tail(2 * nb).cwiseAbs().maxCoeff(), held = b.segment(2 * nb, 2 * nb).cwiseAbs().maxCoeff();
  EXPECT_LT(held, 2.0 * force / 5e11);
  EXPECT_LT((a.head(2 * nb) - b.head(2 * nb)).cwiseAbs().maxCoeff(), 10.0 * held + 1e-14);
  EXPECT_LT((a.tail(2 * nb) - b.tail(2 * nb)).cwiseAbs().maxCoeff(), 10.0 * held + 1e-14);
}

// NLvib's example 02 as it is written: the relative cubic spring reads
// x1 − x2 and acts equally and oppositely (the dynamics balance on each DOF).
TEST(SceneElements, NlvibTwoDofExampleWithTheRelativeSpringSolves) {
  const Scene scene = loadScene(test::problem("field/nlvib-02-2dof-cubic-relative.toml"), {"harmonic_balance.omega=1.0"});
  const LawAttachment& w = scene.model.laws[1].attachment;
  ASSERT_EQ(w.row(0).size(), 2u);
  EXPECT_EQ(w.row(0)[0].dof, 0);
  EXPECT_EQ(w.row(0)[1].dof, 1);
  EXPECT_EQ(w.row(0)[1].weight, -1.0);
  const Eigen::VectorXd full = test::harmonicBalance(scene.model);
  const int nb = scene.model.basis.size();
  // The relative spring's force is −ε (x1 − x2)³ at every sample: its
  // first harmonic against the one of the grounded model differs (it acts).
  const Scene without = loadScene(test::problem("field/nlvib-02-2dof-cubic.toml"),
                                  {"harmonic_balance.omega=1.0", "harmonic_balance.samples=256"});
  const Eigen::VectorXd other = test::harmonicBalance(without.model);
  EXPECT_GT((full.head(2 * nb) - other.head(2 * nb)).cwiseAbs().maxCoeff(), 1e-6);
}

void expectError(const std::string& text, const std::string& needle) {
  test::expectSceneError(text, needle, {}, "bad.toml");
}

using test::replaced;

TEST(SceneElements, BadElementsAreRefusedNamingTheField) {
  const std::string good = jointScene(Eigen::Matrix3d::Identity());
  expectError(replaced(good, "normal = [0, 0, 1]", "normal = [0, 0, 0]"),
              "bad.toml: law[0].normal = [0, 0, 0]: must be a nonzero, finite direction");
  expectError(replaced(good, "tangents = [[1, 0, 0]", "tangents = [[1, 0, 0.1]"),
              "law[0].tangents[0] = [1, 0, 0.1]: must be orthogonal to normal");
  expectError(replaced(good, ", [0, 1, 0]]", ", [0.1, 1, 0]]"),
              "law[0].tangents[1] = [0.1, 1, 0]: must be orthogonal to tangents[0]");
  expectError(replaced(good, "between = [1, 2]", "between = [1, 3]"),
              "law[0].between = 3: no such node (the structure has 2, numbered from 1)");
  expectError(replaced(good, "between = [1, 2]", "between = [2, 2]"), "the two nodes must differ");
  expectError(replaced(good, "normal = [0, 0, 1]", "normal = [0, 1]"),
              "law[0].normal = [0, 1]: must have one entry per DOF of the node (3)");
  expectError(replaced(good, "between = [1, 2]", "between = [1, 2]\ndofs = [1, 2, 3]"),
              "law[0].between = (and dofs or nodes): give between or dofs/nodes, not both");
  expectError(replaced(good, "[[1, 2, 3], [4, 5, 6]]", "[[1, 2, 3], [3, 5, 6]]"),
              "structure.node_table[1] = 3: this DOF is also in node 1");
  expectError(replaced(good, "[[1, 2, 3], [4, 5, 6]]", "[[1, 2, 3], [4, 5, 7]]"),
              "structure.node_table[1] = 7: no such DOF (the structure has 6");
  // A one-component law given three directions.
  const std::string cubic = replaced(replaced(good, "type = \"contact-friction\"", "type = \"cubic\"\nepsilon = 1.0"),
                                     "mu = 0.4\npreload = 1.0\ngap = 0.5\n", "");
  expectError(cubic, "a cubic law reads 1 direction(s) between the nodes");
}

TEST(SceneElements, ANodeTableFileNamesEachNodeOnce) {
  const std::string dir = ::testing::TempDir();
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  };
  const std::string good = write("nodes.txt", "# node dofs\n2 4 5 6\n1 1 2 3  # node 1\n");
  std::string scene = jointScene(Eigen::Matrix3d::Identity());
  const Scene s = parseScene(replaced(scene, "[[1, 2, 3], [4, 5, 6]]", "\"" + good + "\""), "s.toml");
  EXPECT_EQ(s.model.laws[0].attachment.row(0)[1].dof, 5);
  const std::string gap = write("gap.txt", "1 1 2 3\n3 4 5 6\n");
  expectError(replaced(scene, "[[1, 2, 3], [4, 5, 6]]", "\"" + gap + "\""), "nodes must be numbered 1..2 (node 2 is missing)");
  const std::string twice = write("twice.txt", "1 1 2 3\n1 4 5 6\n");
  expectError(replaced(scene, "[[1, 2, 3], [4, 5, 6]]", "\"" + twice + "\""), "line 2) = 1: node listed twice");
}

// A Matrix Market file (coordinate, real, general) of `m`.
std::string matrixMarket(const Eigen::MatrixXd& m) {
  std::string out = "%%MatrixMarket matrix coordinate real general\n" + std::to_string(m.rows()) + " " +
                    std::to_string(m.cols()) + " " + std::to_string(m.size()) + "\n";
  for (int i = 0; i < m.rows(); ++i)
    for (int j = 0; j < m.cols(); ++j)
      out += std::to_string(i + 1) + " " + std::to_string(j + 1) + " " + formatRoundTrip(m(i, j)) + "\n";
  return out;
}

// Two nodes in the plane (x, y) joined by a spring, with elastic friction
// between them (normal y, tangent x), preloaded by their overlap and forced
// along x on node 1, written twice: as `matrices` in node order, and as
// `matrix-market` files whose DOFs are stored in another order, (y1, y2,
// x1, x2), named back by node_table = [[3, 1], [4, 2]]. Read right, the
// table makes them the same model: the same response, DOFs permuted, to
// 1e-10. Read as the identity it is another model.
TEST(SceneElements, AMatrixMarketNodeTableNamesTheStoredDofs) {
  Eigen::MatrixXd m = Eigen::Vector4d(1.0, 1.2, 1.5, 0.8).asDiagonal(), k(4, 4);
  k << 2.0, 0.1, -1.0, 0.0, 0.1, 2.5, 0.0, -1.0, -1.0, 0.0, 2.2, 0.2, 0.0, -1.0, 0.2, 3.0;
  const Eigen::MatrixXd c = 0.03 * k;
  const int stored[4] = {1, 3, 0, 2};  // file DOF i holds node-order DOF stored[i]
  Eigen::PermutationMatrix<4> p;
  for (int i = 0; i < 4; ++i) p.indices()[i] = stored[i];
  auto permuted = [&](const Eigen::MatrixXd& a) { return Eigen::MatrixXd(p.transpose() * a * p); };
  const std::string dir = ::testing::TempDir();
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  };
  const std::string law =
      "[[law]]\ntype = \"elastic-friction\"\nbetween = [1, 2]\nnormal = [0, 1]\ntangents = [[1, 0]]\nmu = 0.3\n"
      "k_t = 2.0\nk_n = 3.0\ngap = -0.2\n"
      "[harmonic_balance]\nharmonics = 5\nset = \"all\"\nsamples = 64\nomega = 1.0\n";
  const std::string in_order = "name = \"pair\"\n[structure]\ntype = \"matrices\"\nmass = " + matrix(m) +
                               "\nstiffness = " + matrix(k) + "\ndamping = " + matrix(c) +
                               "\nnode_table = [[1, 2], [3, 4]]\n[[forcing]]\ndof = 1\ncos = 1.0\n" + law;
  const std::string market = "name = \"pair\"\n[structure]\ntype = \"matrix-market\"\nmass = \"" +
                             write("M.mtx", matrixMarket(permuted(m))) + "\"\nstiffness = \"" +
                             write("K.mtx", matrixMarket(permuted(k))) + "\"\ndamping = \"" +
                             write("C.mtx", matrixMarket(permuted(c))) +
                             "\"\nnode_table = [[3, 1], [4, 2]]\n[[forcing]]\ndof = 3\ncos = 1.0\n" + law;
  const Eigen::VectorXd a = test::solvedAsTheCommandSolves(in_order, dir + "/in-order.toml"),
                        b = test::solvedAsTheCommandSolves(market, dir + "/market.toml");
  const int nb = 11;  // harmonics 0..5
  ASSERT_EQ(a.size(), 6 * nb);
  ASSERT_EQ(b.size(), 6 * nb);
  const double scale = a.cwiseAbs().maxCoeff();
  double mismatch = (a.tail(2 * nb) - b.tail(2 * nb)).cwiseAbs().maxCoeff();  // (p, T)
  for (int i = 0; i < 4; ++i)
    mismatch = std::max(mismatch, (b.segment(i * nb, nb) - a.segment(stored[i] * nb, nb)).cwiseAbs().maxCoeff());
  EXPECT_LT(mismatch, 1e-10 * scale);
  // The element presses and rubs (else the check would hold for any table).
  EXPECT_GT(a.segment(4 * nb, nb).cwiseAbs().maxCoeff(), 0.01 * scale);
  EXPECT_GT(a.segment(5 * nb, nb).cwiseAbs().maxCoeff(), 0.01 * scale);
  // Misread as DOFs in node order, the same files are another model.
  const std::string identity = test::replaced(market, "[[3, 1], [4, 2]]", "[[1, 2], [3, 4]]");
  const Eigen::VectorXd misread = test::solvedAsTheCommandSolves(identity, dir + "/misread.toml");
  EXPECT_GT((misread.tail(2 * nb) - a.tail(2 * nb)).cwiseAbs().maxCoeff(), 1e-3 * scale);
}

}  // namespace
}  // namespace eqhb
