// The space frame (structures/space_frame.h): each of its four parts against
// the closed forms of the clamped-free bar, shaft and beam, its x–z bending
// against the plane frame's, and in a scene its nodes as points in space: a
// joint turned with the frame about its axis gives the turned response.
#include "eqhb/structures/space_frame.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "eqhb/app/modes.h"
#include "eqhb/app/sweep.h"
#include "eqhb/error.h"
#include "eqhb/round_trip.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/structures/beam.h"
#include "eqhb/structures/frame.h"
#include "check_support.h"
#include "command_solve_support.h"
#include "test_support.h"

namespace eqhb {
namespace {

enum { kU, kV, kW, kThetaX, kThetaY, kThetaZ };

// A steel bar 0.6 m long, 20 mm wide (y) and 10 mm high (z): I_z = 4 I_y, so
// the two bending planes differ; J of a thin rectangle, ~ b h³/3 (1 − 0.63 h/b).
SpaceFrameParameters steelBar(int elements) {
  SpaceFrameParameters f;
  f.elements = elements;
  const double b = 0.02, h = 0.01;
  f.section.youngs_modulus = 2.1e11;
  f.section.shear_modulus = 8.1e10;
  f.section.density = 7850.0;
  f.section.area = b * h;
  f.section.second_moment_y = b * h * h * h / 12.0;
  f.section.second_moment_z = h * b * b * b / 12.0;
  f.section.torsion_constant = b * h * h * h / 3.0 * (1.0 - 0.63 * h / b);
  f.length = 0.6;
  return f;
}

std::vector<int> dofsOf(int nodes, const std::vector<int>& components) {
  std::vector<int> out;
  for (int node = 1; node <= nodes; ++node)
    for (int c : components) out.push_back(spaceFrameDof(node, c));
  return out;
}

Eigen::MatrixXd block(const Eigen::SparseMatrix<double>& a, const std::vector<int>& rows, const std::vector<int>& cols) {
  const Eigen::MatrixXd dense(a);
  Eigen::MatrixXd out(rows.size(), cols.size());
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = 0; j < cols.size(); ++j) out(i, j) = dense(rows[i], cols[j]);
  return out;
}

// Generalised eigenvalues of (K, M) on `dofs`, as frequencies (rad/s).
Eigen::VectorXd frequencies(const StructureMatrices& s, const std::vector<int>& dofs) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(block(s.stiffness, dofs, dofs),
                                                                   block(s.mass, dofs, dofs));
  return modes.eigenvalues().cwiseSqrt();
}

BeamParameters beamOf(const SpaceFrameParameters& f, double second_moment) {
  return {f.elements, f.section.youngs_modulus, second_moment, f.section.density * f.section.area, f.length};
}

TEST(SpaceFrame, ItsFourPartsAreUncoupledInAStraightFrame) {
  const StructureMatrices s = cantileverSpaceFrame(steelBar(5));
  ASSERT_EQ(s.dofs(), 30);
  const std::vector<std::vector<int>> parts = {{kU}, {kThetaX}, {kV, kThetaZ}, {kW, kThetaY}};
  for (size_t a = 0; a < parts.size(); ++a)
    for (size_t b = 0; b < parts.size(); ++b) {
      if (a == b) continue;
      EXPECT_EQ(block(s.stiffness, dofsOf(5, parts[a]), dofsOf(5, parts[b])).cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ(block(s.mass, dofsOf(5, parts[a]), dofsOf(5, parts[b])).cwiseAbs().maxCoeff(), 0.0);
    }
  const Eigen::MatrixXd k(s.stiffness), m(s.mass);
  EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
  EXPECT_LT((m - m.transpose()).norm(), 1e-12 * m.norm());
}

// Bending in x–y (v) takes I_z and in x–z (w) I_y: each is the cantilever
// beam's, and with I_z = 4 I_y the v modes are twice the w modes.
TEST(SpaceFrame, EachBendingPlaneIsTheCantileverBeamWithItsSecondMoment) {
  const SpaceFrameParameters frame = steelBar(40);
  const StructureMatrices s = cantileverSpaceFrame(frame);
  const Eigen::VectorXd in_y = frequencies(s, dofsOf(40, {kV, kThetaZ})),
                        in_z = frequencies(s, dofsOf(40, {kW, kThetaY}));
  const auto exact_y = cantileverFrequencies(beamOf(frame, frame.section.second_moment_z), 5),
             exact_z = cantileverFrequencies(beamOf(frame, frame.section.second_moment_y), 5);
  for (int r = 0; r < 5; ++r) {
    EXPECT_GE(in_y[r], exact_y[r] * (1 - 1e-12)) << "mode " << r + 1;  // consistent mass: an upper bound
    EXPECT_LT(in_y[r] / exact_y[r] - 1, 2e-5) << "mode " << r + 1;
    EXPECT_GE(in_z[r], exact_z[r] * (1 - 1e-12)) << "mode " << r + 1;
    EXPECT_LT(in_z[r] / exact_z[r] - 1, 2e-5) << "mode " << r + 1;
    EXPECT_NEAR(in_y[r] / in_z[r], 2.0, 1e-7) << "mode " << r + 1;
  }
}

TEST(SpaceFrame, TorsionConvergesToTheClampedFreeShaft) {
  const SpaceFrameParameters frame = steelBar(60);
  const Eigen::VectorXd fe = frequencies(cantileverSpaceFrame(frame), dofsOf(60, {kThetaX}));
  const auto exact = torsionFrequencies(frame, 4);
  const SpaceFrameSection& s = frame.section;
  const double polar = s.second_moment_y + s.second_moment_z;
  EXPECT_NEAR(exact[0], M_PI / 1.2 * std::sqrt(s.shear_modulus * s.torsion_constant / (s.density * polar)),
              1e-9 * exact[0]);
  for (int r = 0; r < 4; ++r) {
    EXPECT_GE(fe[r], exact[r] * (1 - 1e-12)) << "mode " << r + 1;
    EXPECT_LT(fe[r] / exact[r] - 1, 2e-3) << "mode " << r + 1;
  }
  // Linear elements: the error falls as h².
  const Eigen::VectorXd coarse = frequencies(cantileverSpaceFrame(steelBar(15)), dofsOf(15, {kThetaX}));
  const Eigen::VectorXd fine = frequencies(cantileverSpaceFrame(steelBar(30)), dofsOf(30, {kThetaX}));
  const double ratio = (coarse[1] / exact[1] - 1) / (fine[1] / exact[1] - 1);
  EXPECT_GT(ratio, 3.8);
  EXPECT_LT(ratio, 4.2);
}

// The plane frame's (u, w, θ) with θ = dw/dx is the space frame's
// (u, w, −θy): θy is the right-hand rotation about y, −dw/dx.
TEST(SpaceFrame, ItsXzPlaneIsThePlaneFrameWithTheSlopeTurned) {
  const SpaceFrameParameters space = steelBar(6);
  FrameParameters plane;
  plane.elements = 6;
  plane.section = {space.section.youngs_modulus, space.section.area, space.section.second_moment_y,
                   space.section.density * space.section.area};
  plane.length = space.length;
  const StructureMatrices s = cantileverSpaceFrame(space), p = cantileverFrame(plane);
  Eigen::MatrixXd turn = Eigen::MatrixXd::Zero(18, 18);  // plane-frame DOFs → space-frame ones
  std::vector<int> picked;
  for (int node = 1; node <= 6; ++node) {
    const int at[3] = {kU, kW, kThetaY};
    const double sign[3] = {1.0, 1.0, -1.0};
    for (int c = 0; c < 3; ++c) {
      picked.push_back(spaceFrameDof(node, at[c]));
      turn(3 * (node - 1) + c, 3 * (node - 1) + c) = sign[c];
    }
  }
  const Eigen::MatrixXd kp(p.stiffness), mp(p.mass);
  EXPECT_LT((block(s.stiffness, picked, picked) - turn * kp * turn).norm(), 1e-12 * kp.norm());
  EXPECT_LT((block(s.mass, picked, picked) - turn * mp * turn).norm(), 1e-12 * mp.norm());
}

TEST(SpaceFrame, RefusesNonPositiveParametersNamingThem) {
  auto refused = [](SpaceFrameParameters f) { return test::messageOf([&] { cantileverSpaceFrame(f); }); };
  SpaceFrameParameters f = steelBar(4);
  f.elements = 0;
  EXPECT_NE(refused(f).find("structure.elements"), std::string::npos);
  f = steelBar(4);
  f.section.shear_modulus = 0.0;
  EXPECT_NE(refused(f).find("structure.G"), std::string::npos);
  f = steelBar(4);
  f.section.second_moment_z = -1.0;
  EXPECT_NE(refused(f).find("structure.Iz"), std::string::npos);
  f = steelBar(4);
  f.section.torsion_constant = std::nan("");
  EXPECT_NE(refused(f).find("structure.J"), std::string::npos);
}

std::string vector3(const Eigen::Vector3d& v) {
  return "[" + formatRoundTrip(v[0]) + ", " + formatRoundTrip(v[1]) + ", " + formatRoundTrip(v[2]) + "]";
}

// A round cantilever (I_y = I_z) pressed at its tip against a plane by a
// contact with friction and forced there across and along it; `r` turns the
// contact's directions and the load about the frame's axis x.
std::string tipContactScene(const Eigen::Matrix3d& r) {
  const Eigen::Vector3d load = r * Eigen::Vector3d(0.2, 0.5, 1.0);
  std::string text =
      "name = \"tip\"\n[structure]\ntype = \"space-frame\"\nelements = 4\nE = 2.0\nG = 0.8\nrho = 1.0\nA = 1.0\n"
      "Iy = 0.05\nIz = 0.05\nJ = 0.1\nL = 2.0\nrayleigh = [0.0, 0.02]\n";
  for (int i = 0; i < 3; ++i)  // u, v, w of node 4, numbered from 1
    text += "[[forcing]]\ndof = " + std::to_string(spaceFrameDof(4, i) + 1) + "\nharmonic = 1\ncos = " +
            formatRoundTrip(load[i]) + "\n";
  text += "[[law]]\ntype = \"contact-friction\"\nbetween = [4]\nnormal = " + vector3(r * Eigen::Vector3d(0, 0, 1)) +
          "\ntangents = [" + vector3(r * Eigen::Vector3d(1, 0, 0)) + ", " + vector3(r * Eigen::Vector3d(0, 1, 0)) +
          "]\nmu = 0.3\npreload = 0.5\ngap = 0.0\n";
  return text + "[harmonic_balance]\nharmonics = 3\nset = \"all\"\nsamples = 64\nomega = 0.15\n";
}

TEST(SpaceFrame, SceneNodesAreThePointsOfItsAxis) {
  const Scene scene = parseScene(tipContactScene(Eigen::Matrix3d::Identity()), "tip.toml");
  ASSERT_EQ(scene.model.structure.dofs(), 24);
  const LawAttachment& w = scene.model.laws[0].attachment;
  ASSERT_EQ(w.dimension(), 3);
  EXPECT_TRUE(w.grounded());
  EXPECT_EQ(w.row(0)[0].dof, spaceFrameDof(4, kW));  // normal z
  EXPECT_EQ(w.row(1)[0].dof, spaceFrameDof(4, kU));  // t1 = x
  EXPECT_EQ(w.row(2)[0].dof, spaceFrameDof(4, kV));  // t2 = y
  EXPECT_EQ(scene.model.dof_names[spaceFrameDof(3, kThetaY)], "thetay3");
  EXPECT_EQ(scene.model.dof_names[spaceFrameDof(4, kV)], "v4");
  SpaceFrameParameters p;
  p.elements = 4;
  p.section = {2.0, 0.8, 1.0, 1.0, 0.05, 0.05, 0.1};
  p.length = 2.0;
  const StructureMatrices direct = cantileverSpaceFrame(p);
  EXPECT_LT((Eigen::MatrixXd(scene.model.structure.stiffness) - Eigen::MatrixXd(direct.stiffness)).norm(), 1e-12);
  EXPECT_LT((Eigen::MatrixXd(scene.model.structure.damping) - 0.02 * Eigen::MatrixXd(direct.stiffness)).norm(),
            1e-12);
  const std::string good = tipContactScene(Eigen::Matrix3d::Identity());
  test::expectSceneError(test::replaced(good, "Iy = 0.05", "Iy = 0.0"), "structure.Iy = 0: must be finite and > 0");
  test::expectSceneError(test::replaced(good, "G = 0.8\n", ""), "structure.G");
  test::expectSceneError(test::replaced(good, "normal = [0, 0, 1]", "normal = [0, 0, 1, 0, 0, 0]"),
                         "law[0].normal = [0, 0, 1, 0, 0, 0]: must have one entry per DOF of the node (3)");
  test::expectSceneError(test::replaced(good, "between = [4]", "between = [5]"), "law[0].between = 5: no such node");
}

// Turning the contact plane and the load about x turns (v, w) and
// (θy, θz) alike and leaves u, θx and the contact forces as they were.
TEST(SpaceFrame, AJointTurnedWithTheFrameAboutItsAxisGivesTheTurnedResponse) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Scene scene = parseScene(tipContactScene(Eigen::Matrix3d::Identity()), "axes.toml");
  const Eigen::VectorXd a = test::solvedAsTheCommandSolves(tipContactScene(Eigen::Matrix3d::Identity()), "axes.toml"),
                        b = test::solvedAsTheCommandSolves(tipContactScene(r), "turned.toml");
  const int nb = scene.model.basis.size(), dofs = scene.model.structure.dofs();
  const double scale = a.head(dofs * nb).cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  // The contact slides and lifts off part of the period: not a linear response.
  const Eigen::VectorXd normal_force = a.segment(dofs * nb, nb);
  ASSERT_GT(normal_force.tail(nb - 1).cwiseAbs().maxCoeff(), 0.05 * std::abs(normal_force[0]));
  double worst = 0.0;
  for (int node = 1; node <= 4; ++node)
    for (int t = 0; t < nb; ++t) {
      auto at = [&](const Eigen::VectorXd& x, int c) { return x[spaceFrameDof(node, c) * nb + t]; };
      const Eigen::Vector3d translation(at(a, kU), at(a, kV), at(a, kW)), rotation(at(a, kThetaX), at(a, kThetaY),
                                                                                     at(a, kThetaZ));
      const Eigen::Vector3d turned_translation(at(b, kU), at(b, kV), at(b, kW)),
          turned_rotation(at(b, kThetaX), at(b, kThetaY), at(b, kThetaZ));
      worst = std::max({worst, (r * translation - turned_translation).norm(), (r * rotation - turned_rotation).norm()});
    }
  EXPECT_LT(worst, 1e-9 * scale);
  EXPECT_LT((a.tail(a.size() - dofs * nb) - b.tail(b.size() - dofs * nb)).cwiseAbs().maxCoeff(), 1e-9 * scale);
}

struct Peak {
  double omega = 0.0, amplitude = 0.0;
};

Peak peakOf(const Curve& curve, int dof) {
  Peak peak;
  for (const CurvePoint& p : curve.points)
    if (p.converged && p.max_abs[dof] > peak.amplitude) peak = {p.omega, p.max_abs[dof]};
  return peak;
}

// The lowest frequency of (K + springs, M): the blade's flapwise mode.
double lowestFrequency(Eigen::MatrixXd k, const Eigen::MatrixXd& m) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(k, m);
  return std::sqrt(modes.eigenvalues()[0]);
}

// problems/blade-tip-damper.toml: the damper's resonance lies between the
// blade's with its tip free and held by the damper's springs, and under a
// light preload the tip slides and the resonance is the free blade's.
TEST(SpaceFrame, TheTipDampersResonanceLiesBetweenTheFreeAndTheHeldBlades) {
  app::SceneSettings scene;
  scene.path = test::problem("blade-tip-damper.toml");
  const app::SweepResult pressed = app::sweep(scene, app::SweepOptions{});
  ASSERT_EQ(pressed.curve.failed_points, 0);
  ASSERT_TRUE(pressed.curve.complete);
  const LinearStructure& blade = pressed.model.structure;
  const Eigen::MatrixXd k(blade.stiffness), m(blade.mass);
  const int u = spaceFrameDof(8, kU), v = spaceFrameDof(8, kV), w = spaceFrameDof(8, kW);
  Eigen::MatrixXd held = k;
  held(u, u) += 1e5;  // k_t
  held(w, w) += 1e5;
  held(v, v) += 1e7;  // k_n
  const double free_mode = lowestFrequency(k, m), held_mode = lowestFrequency(held, m);
  EXPECT_NEAR(free_mode, 656.0, 2.0);  // 3.516 sqrt(E I_y / (ρ A L⁴))
  const Peak at_4n = peakOf(pressed.curve, w);
  EXPECT_GT(at_4n.omega, 1.05 * free_mode);
  EXPECT_LT(at_4n.omega, 0.95 * held_mode);
  scene.overrides = {"preload[0].force=1"};
  const app::SweepResult light = app::sweep(scene, app::SweepOptions{});
  ASSERT_EQ(light.curve.failed_points, 0);
  const Peak at_1n = peakOf(light.curve, w);
  EXPECT_NEAR(at_1n.omega, free_mode, 0.02 * free_mode);
  EXPECT_GT(at_1n.amplitude, 10.0 * at_4n.amplitude);
}

// The damper's nonlinear mode 1 on the default range: the damper's limit is
// μ times the preload's normal force, which the law does not hold itself,
// so the range is set from the static state's limit: it starts where the
// damper holds the tip (the held blade's 1389.5 rad/s), passes through the
// microslip where the forced resonance lies (770) and ends on the free
// blade's mode. Before, the range was the scene's length scale and started
// 60 times above slip onset, the first point failing and the rest on the
// free blade's 657.
TEST(SpaceFrame, TheTipDampersModeRunsFromTheHeldToTheFreeBlade) {
  app::SceneSettings scene;
  scene.path = test::problem("blade-tip-damper.toml");
  app::ModesOptions o;
  o.points = 20;
  const app::ModesRun run = app::modes(scene, o);
  ASSERT_TRUE(run.backbone.complete());
  EXPECT_NEAR(run.backbone.start.omega, 1389.52, 0.01);
  const std::vector<BackbonePoint>& points = run.backbone.points;
  EXPECT_NEAR(points.front().omega, run.backbone.start.omega, 1e-6 * run.backbone.start.omega);
  EXPECT_NEAR(points.back().omega, 656.2, 0.01 * 656.2);
  bool below = false, above = false;  // the forced resonance's 770 is crossed
  for (const BackbonePoint& p : points) (p.omega > 770.0 ? above : below) = true;
  EXPECT_TRUE(below && above);
}

}  // namespace
}  // namespace eqhb
