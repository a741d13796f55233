// The plane frame (structures/frame.h) and the lap joint built from it
// (structures/lap_joint.h): the frame's axial and bending frequencies against
// the closed forms of the clamped-free bar and beam, the lap joint's surface
// coordinates, and the structures' input errors.
#include "eqhb/structures/frame.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>

#include "eqhb/error.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/structures/beam.h"
#include "eqhb/structures/lap_joint.h"
#include "test_support.h"

namespace eqhb {
namespace {

// A steel bar 0.6 m long, 20 x 10 mm: axial modes far above the bending ones.
FrameParameters steelFrame(int elements) {
  FrameParameters f;
  f.elements = elements;
  f.section = {2.1e11, 2e-4, 2e-4 * 1e-4 / 12.0, 7850.0 * 2e-4};
  f.length = 0.6;
  return f;
}

// Generalised eigenvalues ω² of (K, M) restricted to the DOFs of `component`.
Eigen::VectorXd frequencies(const StructureMatrices& s, const std::vector<int>& dofs) {
  const Eigen::MatrixXd k(s.stiffness), m(s.mass);
  const Eigen::Index n = static_cast<Eigen::Index>(dofs.size());
  Eigen::MatrixXd kk(n, n), mm(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      kk(i, j) = k(dofs[i], dofs[j]);
      mm(i, j) = m(dofs[i], dofs[j]);
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(kk, mm);
  return modes.eigenvalues().cwiseSqrt();
}

std::vector<int> dofsOf(int nodes, std::vector<int> components) {
  std::vector<int> out;
  for (int node = 1; node <= nodes; ++node)
    for (int c : components) out.push_back(frameDof(node, c));
  return out;
}

TEST(Frame, AxialAndBendingAreUncoupledInAStraightFrame) {
  const StructureMatrices s = cantileverFrame(steelFrame(8));
  ASSERT_EQ(s.dofs(), 24);
  const Eigen::MatrixXd k(s.stiffness), m(s.mass);
  for (int node = 1; node <= 8; ++node)
    for (int other = 1; other <= 8; ++other)
      for (int c : {1, 2}) {
        EXPECT_EQ(k(frameDof(node, 0), frameDof(other, c)), 0.0);
        EXPECT_EQ(m(frameDof(node, 0), frameDof(other, c)), 0.0);
      }
}

TEST(Frame, AxialFrequenciesConvergeToTheClampedFreeBar) {
  const FrameParameters frame = steelFrame(60);
  const StructureMatrices s = cantileverFrame(frame);
  const Eigen::VectorXd fe = frequencies(s, dofsOf(60, {0}));
  const auto exact = axialBarFrequencies(frame, 4);
  // ω_1 = π/(2L) sqrt(E/ρ) = 4. 3 kHz for steel over 0.6 m.
  EXPECT_NEAR(exact[0], M_PI / 1.2 * std::sqrt(2.1e11 / 7850.0), 1e-6 * exact[0]);
  for (int r = 0; r < 4; ++r) {
    EXPECT_GE(fe[r], exact[r] * (1 - 1e-12)) << "mode " << r + 1;  // consistent mass: an upper bound
    EXPECT_LT(fe[r] / exact[r] - 1, 2e-3) << "mode " << r + 1;
  }
  // Linear elements: the error falls as h² (halving h divides it by ~4).
  const Eigen::VectorXd coarse = frequencies(cantileverFrame(steelFrame(15)), dofsOf(15, {0}));
  const Eigen::VectorXd fine = frequencies(cantileverFrame(steelFrame(30)), dofsOf(30, {0}));
  const double ratio = (coarse[1] / exact[1] - 1) / (fine[1] / exact[1] - 1);
  EXPECT_GT(ratio, 3.8);
  EXPECT_LT(ratio, 4.2);
}

TEST(Frame, BendingFrequenciesAreTheCantileverBeams) {
  const FrameParameters frame = steelFrame(40);
  const StructureMatrices s = cantileverFrame(frame);
  // All modes of the frame: the bending ones among them are the beam's.
  const Eigen::VectorXd all = frequencies(s, dofsOf(40, {0, 1, 2}));
  BeamParameters beam{40, frame.section.youngs_modulus, frame.section.second_moment, frame.section.mass_per_length,
                      frame.length};
  const auto exact = cantileverFrequencies(beam, 5);
  for (int r = 0; r < 5; ++r) {
    // ω_1 of the bending modes is far below the first axial one: the lowest
    // five are bending.
    EXPECT_GE(all[r], exact[r] * (1 - 1e-12)) << "mode " << r + 1;
    EXPECT_LT(all[r] / exact[r] - 1, 2e-5) << "mode " << r + 1;
  }
  // The bending block is the beam's element by element.
  const Eigen::VectorXd bending = frequencies(s, dofsOf(40, {1, 2}));
  const StructureMatrices b = cantileverBeam(beam);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> beam_modes{Eigen::MatrixXd(b.stiffness),
                                                                       Eigen::MatrixXd(b.mass)};
  for (int r = 0; r < 10; ++r) EXPECT_NEAR(bending[r], std::sqrt(beam_modes.eigenvalues()[r]), 1e-9 * bending[r]);
}

TEST(Frame, RefusesNonPositiveParametersNamingThem) {
  auto refused = [](FrameParameters f) { return test::messageOf([&] { cantileverFrame(f); }); };
  FrameParameters f = steelFrame(4);
  f.elements = 0;
  EXPECT_NE(refused(f).find("structure.elements"), std::string::npos);
  f = steelFrame(4);
  f.section.area = 0.0;
  EXPECT_NE(refused(f).find("structure.A"), std::string::npos);
  f = steelFrame(4);
  f.section.youngs_modulus = -1.0;
  EXPECT_NE(refused(f).find("structure.E"), std::string::npos);
  f = steelFrame(4);
  f.length = std::nan("");
  EXPECT_NE(refused(f).find("structure.L"), std::string::npos);
}

// In a scene: a frame's node i is [u, w, θ], so an element names a node and
// a direction over those three; a lap joint's nodes are its facing surfaces.
TEST(Frame, SceneNodesAreTheFramesNodes) {
  const std::string frame =
      "name = \"frame\"\n[structure]\ntype = \"frame\"\nelements = 4\nE = 2.0\nA = 3.0\nI = 0.5\nrhoA = 1.0\n"
      "L = 2.0\nrayleigh = [0.0, 0.01]\n[[law]]\ntype = \"cubic\"\nbetween = [4, 2]\nnormal = [0, 1, 0]\n"
      "epsilon = 1.0\n[harmonic_balance]\nharmonics = 3\nsamples = 16\nomega = 1.0\n";
  const Scene scene = parseScene(frame, "frame.toml");
  ASSERT_EQ(scene.model.structure.dofs(), 12);
  const LawAttachment& w = scene.model.laws[0].attachment;
  ASSERT_EQ(w.row(0).size(), 2u);
  EXPECT_EQ(w.row(0)[0].dof, frameDof(4, 1));
  EXPECT_EQ(w.row(0)[0].weight, 1.0);
  EXPECT_EQ(w.row(0)[1].dof, frameDof(2, 1));
  EXPECT_EQ(w.row(0)[1].weight, -1.0);
  // The scene's stiffness is cantileverFrame's with C = 0.01 K.
  FrameParameters p;
  p.elements = 4;
  p.section = {2.0, 3.0, 0.5, 1.0};
  p.length = 2.0;
  const StructureMatrices direct = cantileverFrame(p);
  EXPECT_LT((Eigen::MatrixXd(scene.model.structure.stiffness) - Eigen::MatrixXd(direct.stiffness)).norm(), 1e-12);
  EXPECT_LT((Eigen::MatrixXd(scene.model.structure.damping) - 0.01 * Eigen::MatrixXd(direct.stiffness)).norm(), 1e-12);
  // A bad value names its field.
  std::string bad = frame;
  bad.replace(bad.find("A = 3.0"), 7, "A = 0.0");
  EXPECT_NE(test::messageOf([&] { parseScene(bad, "frame.toml"); }).find("structure.A"), std::string::npos);
  // A direction of the wrong length for a frame node is refused.
  std::string short_normal = frame;
  short_normal.replace(short_normal.find("normal = [0, 1, 0]"), 18, "normal = [0, 1]");
  EXPECT_NE(test::messageOf([&] { parseScene(short_normal, "frame.toml"); }).find("law[0].normal"),
            std::string::npos);
}

LapJointParameters smallJoint() {
  LapJointParameters p;
  p.pairs = 5;
  p.elements = 6;
  p.length = 0.4;
  p.overlap = 0.1;
  p.thickness = 0.02;
  p.width = 0.03;
  p.youngs_modulus = 2e11;
  p.density = 7800.0;
  return p;
}

// Kinetic energy of a rigid axial translation of both beams' free nodes: the
// surface coordinates carry it as u_s = u (θ = 0).
TEST(LapJoint, SurfaceCoordinatesReadTheFacingSurfaces) {
  const LapJointParameters p = smallJoint();
  const LapJoint joint = lapJoint(p);
  ASSERT_EQ(joint.beam_nodes, 10);
  ASSERT_EQ(joint.matrices.dofs(), 60);
  ASSERT_EQ(joint.surfaces.size(), 10u);
  // A pure rotation θ of the upper beam's pair nodes, u kept 0: in surface
  // coordinates u_s = (h/2) θ there. Build the physical field, map to x̃ and
  // compare strain energies: K̃ = Tᵀ K T.
  const Eigen::MatrixXd k(joint.matrices.stiffness);
  EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
  // The upper beam's surface node at pair k is its node elements + k − 1.
  for (int pair = 1; pair <= p.pairs; ++pair) {
    const std::vector<int>& upper = joint.surfaces[pair - 1];
    const std::vector<int>& lower = joint.surfaces[p.pairs + pair - 1];
    EXPECT_EQ(upper[0], lapJointDof(10, 0, p.elements + pair - 1, 0));
    EXPECT_EQ(upper[1], lapJointDof(10, 0, p.elements + pair - 1, 1));
    EXPECT_EQ(lower[0], lapJointDof(10, 1, p.elements + p.pairs - pair, 0));
  }
  // Glue the surfaces (stiff springs on u_s and w of each pair): the joint is
  // then one clamped-clamped beam of thickness h outside and 2h (two layers
  // sliding nowhere) over the overlap. Its static stiffness under a mid-span
  // load lies between the clamped-clamped beam of thickness h over the whole
  // span 2L − overlap (softer) and one of thickness 2h (stiffer).
  Eigen::MatrixXd glued = k;
  const double spring = 1e4 * k.diagonal().maxCoeff();
  for (int pair = 0; pair < p.pairs; ++pair)
    for (int c = 0; c < 2; ++c) {
      const int a = joint.surfaces[pair][c], b = joint.surfaces[p.pairs + pair][c];
      glued(a, a) += spring;
      glued(b, b) += spring;
      glued(a, b) -= spring;
      glued(b, a) -= spring;
    }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(60);
  const int middle = lapJointDof(10, 0, p.elements + 2, 1);  // pair 3 of 5: mid-span
  f[middle] = 1.0;
  const double deflection = glued.ldlt().solve(f)[middle];
  // The same span as one frame: thickness h outside, 2h over the overlap
  // (the glued layers bend as one section of 8 I), on the same elements.
  FrameSection thin{p.youngs_modulus, p.width * p.thickness, p.width * p.thickness * p.thickness * p.thickness / 12.0,
                    p.density * p.width * p.thickness};
  FrameSection thick{p.youngs_modulus, 2 * thin.area, 8 * thin.second_moment, 2 * thin.mass_per_length};
  std::vector<Eigen::Triplet<double>> kt, mt;
  const int elements = 2 * p.elements + p.pairs - 1;  // nodes 0 and `elements` clamped
  for (int e = 0; e < elements; ++e) {
    std::array<int, 6> dofs;
    for (int c = 0; c < 3; ++c) {
      dofs[c] = e == 0 ? -1 : 3 * (e - 1) + c;
      dofs[3 + c] = e + 1 == elements ? -1 : 3 * e + c;
    }
    const bool lap = e >= p.elements && e < p.elements + p.pairs - 1;
    addFrameElement(lap ? thick : thin, lap ? p.overlap / (p.pairs - 1) : (p.length - p.overlap) / p.elements, dofs,
                    &kt, &mt);
  }
  Eigen::SparseMatrix<double> stepped(3 * (elements - 1), 3 * (elements - 1));
  stepped.setFromTriplets(kt.begin(), kt.end());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(stepped.rows());
  const int centre = 3 * (p.elements + 2 - 1) + 1;  // node p.elements + 2 from the left clamp
  g[centre] = 1.0;
  const double solid = Eigen::MatrixXd(stepped).ldlt().solve(g)[centre];
  // Node-wise gluing of linear axial and cubic bending fields is stiffer
  // than the solid section between nodes: 3 % with 4 elements over the lap.
  EXPECT_NEAR(deflection / solid, 1.0, 0.05) << deflection << " vs " << solid;
  // The gluing is what couples the beams: without it (no contact at all)
  // the middle load bends the upper cantilever alone, w(L) = x²(3L − x)/(6EI)
  // under a load at x.
  const double ei = thin.youngs_modulus * thin.second_moment;
  const Eigen::VectorXd alone = Eigen::MatrixXd(k).ldlt().solve(f);
  const double x = p.length - p.overlap / 2;
  EXPECT_NEAR(alone[lapJointDof(10, 0, 10, 1)], x * x * (3 * p.length - x) / (6 * ei), 1e-9 * alone.norm());
  // Pure bending (u = 0 on the axis): the upper beam's lower surface slides by
  // u + (h/2) θ = (h/2) θ, read as its surface DOF.
  for (int pair = 1; pair <= p.pairs; ++pair) {
    const int node = p.elements + pair - 1;
    EXPECT_NEAR(alone[lapJointDof(10, 0, node, 0)], 0.5 * p.thickness * alone[lapJointDof(10, 0, node, 2)],
                1e-9 * alone.norm());
  }
  // The same load on the lower beam: its upper surface slides by u − (h/2) θ.
  Eigen::VectorXd lower_load = Eigen::VectorXd::Zero(60);
  lower_load[lapJointDof(10, 1, p.elements + 2, 1)] = 1.0;
  const Eigen::VectorXd lower = Eigen::MatrixXd(k).ldlt().solve(lower_load);
  for (int pair = 1; pair <= p.pairs; ++pair) {
    const int node = p.elements + p.pairs - pair;
    EXPECT_NE(lower[lapJointDof(10, 1, node, 2)], 0.0);
    EXPECT_NEAR(lower[lapJointDof(10, 1, node, 0)], -0.5 * p.thickness * lower[lapJointDof(10, 1, node, 2)],
                1e-9 * lower.norm());
  }
}

TEST(LapJoint, RefusesBadParametersNamingThem) {
  auto refused = [](LapJointParameters p) { return test::messageOf([&] { lapJoint(p); }); };
  LapJointParameters p = smallJoint();
  p.pairs = 1;
  EXPECT_NE(refused(p).find("structure.pairs"), std::string::npos);
  p = smallJoint();
  p.overlap = 0.0;
  EXPECT_NE(refused(p).find("structure.overlap"), std::string::npos);
  p = smallJoint();
  p.overlap = p.length;
  EXPECT_NE(refused(p).find("structure.overlap"), std::string::npos);
  p = smallJoint();
  p.thickness = 0.0;
  EXPECT_NE(refused(p).find("structure.h"), std::string::npos);
  p = smallJoint();
  p.youngs_modulus = -2e11;
  EXPECT_NE(refused(p).find("structure.E"), std::string::npos);
  p = smallJoint();
  p.density = 0.0;
  EXPECT_NE(refused(p).find("structure.rho"), std::string::npos);
  p = smallJoint();
  p.elements = 0;
  EXPECT_NE(refused(p).find("structure.elements"), std::string::npos);
}

}  // namespace
}  // namespace eqhb
