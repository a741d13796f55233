// What the outputs show: DOF names of beams and frames, the default choice
// (a beam's tip deflection defines the peak, not its tip rotation), the
// scene's [output] and the errors for DOFs that are not there.
#include "eqhb/scenes/dof_choice.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "eqhb/curves/curve_writers.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/scenes/scene.h"
#include "check_support.h"
#include "test_support.h"

namespace eqhb {
namespace {

const char* kBeam = R"(
name = "b"
[structure]
type = "beam"
elements = 10
E = 1.0
I = 1.0
rhoA = 1.0
L = 1.0
[[forcing]]
node = 10
cos = 1.0
[harmonic_balance]
harmonics = 1
samples = 8
omega = 1.0
)";

const char* kChain = R"(
name = "c"
[structure]
type = "chain"
dofs = 3
m = 1.0
k = 1.0
d = 0.1
[[forcing]]
dof = 1
cos = 1.0
[harmonic_balance]
harmonics = 1
samples = 8
omega = 1.0
)";

// The InputError's message of `load`, "" when it loads.
std::string errorOf(const std::string& text) {
  try {
    parseScene(text, "scene.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DofChoice, BeamDofsAreNamedDeflectionAndRotationPerNode) {
  const Scene scene = parseScene(kBeam, "scene.toml");
  ASSERT_EQ(scene.model.structure.dofs(), 20);
  EXPECT_EQ(dofLabel(scene.model, 0), "w1");
  EXPECT_EQ(dofLabel(scene.model, 1), "theta1");
  EXPECT_EQ(dofLabel(scene.model, 18), "w10");
  EXPECT_EQ(dofLabel(scene.model, 19), "theta10");
  // The solution's channels carry the names (text, JSON and Python read them).
  const HbSolution s = summarize(scene.model, Eigen::VectorXd::Zero(20 * scene.model.basis.size()));
  EXPECT_EQ(s.displacements[19].label, "theta10");
}

TEST(DofChoice, FrameDofsAreNamedAxialDeflectionAndRotation) {
  std::string text = kBeam;
  text.replace(text.find("type = \"beam\""), 13, "type = \"frame\"\nA = 1.0");
  text.replace(text.find("node = 10"), 9, "dof = 29");
  const Scene scene = parseScene(text, "scene.toml");
  EXPECT_EQ(dofLabel(scene.model, 0), "u1");
  EXPECT_EQ(dofLabel(scene.model, 4), "w2");
  EXPECT_EQ(dofLabel(scene.model, 29), "theta10");
  EXPECT_EQ(scene.output.peak, 28);  // w10, the free end's deflection
}

TEST(DofChoice, ABeamShowsFourDeflectionsAndItsTipDeflectionDefinesThePeak) {
  const Scene scene = parseScene(kBeam, "scene.toml");
  // Nodes 3, 5, 8 and 10: a quarter, half, three quarters and the tip.
  EXPECT_EQ(scene.output.shown, (std::vector<int>{4, 8, 14, 18}));
  EXPECT_EQ(scene.output.peak, 18);
  const Scene shipped = loadScene(test::problem("beam-damper.toml"));
  EXPECT_EQ(dofLabel(shipped.model, shipped.output.peak), "w60");
}

TEST(DofChoice, OtherStructuresShowEveryDofAndTheLastDefinesThePeak) {
  const Scene scene = parseScene(kChain, "scene.toml");
  EXPECT_EQ(scene.output.shown, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(scene.output.peak, 2);
  EXPECT_EQ(dofLabel(scene.model, 2), "x3");
}

TEST(DofChoice, ALargerStructureWithoutNamesShowsFourDofsSpreadUpToTheLast) {
  std::string text = kChain;
  text.replace(text.find("dofs = 3"), 8, "dofs = 12");
  const Scene scene = parseScene(text, "scene.toml");
  EXPECT_EQ(scene.output.shown, (std::vector<int>{2, 5, 8, 11}));
  EXPECT_EQ(scene.output.peak, 11);
  EXPECT_EQ(shownDofsNote(scene.model, scene.output),
            "x3, x6, x9, x12 of 12 DOFs shown; others by --show or [output] dofs, by number or name");
  text.replace(text.find("dofs = 12"), 9, "dofs = 8");  // up to kEveryDofShownUpTo: every DOF
  const Scene small = parseScene(text, "scene.toml");
  EXPECT_EQ(small.output.shown, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(shownDofsNote(small.model, small.output), "");
  const Scene beam = parseScene(kBeam, "scene.toml");
  EXPECT_EQ(shownDofsNote(beam.model, beam.output),
            "w3, w5, w8, w10 of 20 DOFs shown; others by --show or [output] dofs, by number or name (\"w1\")");
  // A choice in another order is not "every DOF".
  DofChoice reversed{{2, 1, 0}, 0};
  EXPECT_NE(shownDofsNote(parseScene(kChain, "scene.toml").model, reversed), "");
}

TEST(DofChoice, LapJointDofsAreNamedByBeamNodeAndDirection) {
  const Scene scene = loadScene(test::problem("lap-joint.toml"));
  ASSERT_EQ(scene.model.structure.dofs(), 180);
  // DOF (0-based) and its name. The upper beam's nodes 1..30 from its clamp,
  // the lower beam's 31..60 from its own; over the lap (upper nodes 10..30,
  // lower 40..60: pair k is nodes 9 + k and 61 − k) the axial DOF is the
  // facing surface's slide.
  const std::vector<std::pair<int, std::string>> names = {
      {0, "u1"},    {1, "w1"},     {2, "theta1"},  {26, "theta9"}, {27, "us10"},  {87, "us30"},
      {90, "u31"},  {114, "u39"},  {117, "us40"},  {177, "us60"},  {178, "w60"},  {179, "theta60"}};
  for (const auto& [dof, name] : names) EXPECT_EQ(dofLabel(scene.model, dof), name) << "DOF " << dof;
  // The scene's forcing (DOF 59) is the upper beam's w20, which [output] makes the peak.
  EXPECT_EQ(resolveDof(scene.model, "59", "dof"), resolveDof(scene.model, "w20", "dof"));
  EXPECT_EQ(dofLabel(scene.model, scene.output.peak), "w20");
  EXPECT_EQ(scene.output.shown, (std::vector<int>{28, 58, 88, 148}));
  EXPECT_THROW(resolveDof(scene.model, "u10", "show"), InputError);  // node 10's axial DOF is us10
}

TEST(DofChoice, TheSceneChoosesByNumberOrName) {
  const Scene scene =
      parseScene(std::string(kBeam) + "[output]\ndofs = [\"w10\", 3, \"x6\", \"theta2\"]\npeak = \"theta10\"\n", "s.toml");
  EXPECT_EQ(scene.output.shown, (std::vector<int>{18, 2, 5, 3}));
  EXPECT_EQ(scene.output.peak, 19);
}

// A load names its DOF as [output] does: "theta10" is DOF 20, node 10's
// rotation, which `node` (a beam node's deflection) cannot name.
TEST(DofChoice, ALoadNamesItsDofByNumberOrName) {
  const std::string by_name = test::replaced(kBeam, "node = 10\n", "dof = \"theta10\"\n");
  const std::string by_number = test::replaced(kBeam, "node = 10\n", "dof = 20\n");
  const Scene named = parseScene(by_name, "s.toml"), numbered = parseScene(by_number, "s.toml");
  ASSERT_EQ(named.model.structure.loads.size(), 1u);
  EXPECT_EQ(named.model.structure.loads[0].dof, 19);
  EXPECT_EQ(numbered.model.structure.loads[0].dof, 19);
  const std::string preloaded = test::replaced(by_name, "[harmonic_balance]\n",
                                               "[[preload]]\ndof = \"w4\"\nforce = 2.0\n[harmonic_balance]\nset = \"all\"\n");
  const Scene with_preload = parseScene(preloaded, "s.toml");
  ASSERT_EQ(with_preload.preload.size(), 1u);
  EXPECT_EQ(with_preload.preload[0].dof, 6);  // w4: DOF 7 from 1
  EXPECT_NE(errorOf(test::replaced(kBeam, "node = 10\n", "dof = \"w11\"\n")).find("scene.toml: forcing[0].dof = \"w11\": no DOF"),
            std::string::npos);
  EXPECT_NE(errorOf(test::replaced(preloaded, "dof = \"w4\"", "dof = \"v4\"")).find("preload[0].dof = \"v4\": no DOF"),
            std::string::npos);
}

TEST(DofChoice, DofsOutsideTheStructureOrAnEmptyListNameTheField) {
  const std::string beam = kBeam;
  EXPECT_NE(errorOf(beam + "[output]\ndofs = [\"w11\"]\n").find("output.dofs[0] = \"w11\": no DOF"), std::string::npos)
      << errorOf(beam + "[output]\ndofs = [\"w11\"]\n");
  EXPECT_NE(errorOf(beam + "[output]\ndofs = [21]\n").find("output.dofs[0] = \"21\": no such DOF (the structure has 20"),
            std::string::npos);
  EXPECT_NE(errorOf(beam + "[output]\ndofs = []\n").find("output.dofs = []: give at least one DOF"), std::string::npos);
  EXPECT_NE(errorOf(beam + "[output]\ndofs = [1, \"w1\"]\n").find("output.dofs[1] = \"w1\": names a DOF given before"),
            std::string::npos);
  EXPECT_NE(errorOf(beam + "[output]\npeak = 0\n").find("output.peak = \"0\": no such DOF"), std::string::npos);
  EXPECT_NE(errorOf(beam + "[output]\npeak = 1.5\n").find("output.peak"), std::string::npos);
  EXPECT_NE(errorOf(beam + "[output]\nshow = [1]\n").find("show"), std::string::npos);
  const Scene chain = parseScene(kChain, "scene.toml");
  EXPECT_THROW(resolveDof(chain.model, "w1", "show"), InputError);
  EXPECT_THROW(resolveDof(chain.model, "x4", "show"), InputError);
  EXPECT_EQ(resolveDof(chain.model, "x3", "show"), 2);
}

TEST(DofChoice, TheCsvShowsTheChosenDofsUnderTheirNames) {
  const Scene scene = parseScene(kBeam, "scene.toml");
  Curve curve;
  CurvePoint p;
  p.converged = true;
  for (int i = 1; i <= 20; ++i) {
    p.max_abs.push_back(i);
    p.first_harmonic.push_back(100 + i);
  }
  curve.points.push_back(p);
  const std::string path = ::testing::TempDir() + "dof_choice_test.csv";
  writeCurveCsv(path, curve, curveColumns(scene.model, {18, 2}));
  std::ifstream in(path);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_NE(header.find(",seconds,max_abs_w10,max_abs_w2,first_harmonic_w10,first_harmonic_w2,energy"),
            std::string::npos)
      << header;
  EXPECT_NE(row.find(",19,3,119,103,"), std::string::npos) << row;
  std::remove(path.c_str());
  // The summary's peak is the chosen DOF's, under its name.
  CurvePoint q = p;
  q.max_abs[18] = 0.5;  // lower tip deflection, higher elsewhere
  q.max_abs[19] = 50.0;
  q.omega = 2.0;
  curve.points.push_back(q);
  CurveRun run;
  run.model = &scene.model;
  run.peak_dof = scene.output.peak;
  std::ostringstream text;
  writeCurveSummary(text, curve, run);
  EXPECT_NE(text.str().find("peak: omega = 0, max|w10| = 19\n"), std::string::npos) << text.str();
}

}  // namespace
}  // namespace eqhb
