#include "eqhb/scenes/scene_generator.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/backends/registry.h"

namespace eqhb {
namespace {

TEST(SceneGenerator, ChainSceneHasTheRequestedSizeAndContacts) {
  ChainSceneSpec spec;
  spec.dofs = 40;
  spec.contacts = 4;
  spec.harmonics = 3;
  const Scene s = parseScene(chainSceneText(spec), "chain.toml");
  EXPECT_EQ(s.model.structure.dofs(), 40);
  ASSERT_EQ(s.model.laws.size(), 4u);
  EXPECT_EQ(s.model.laws[0].attachment.dof(0), 9);   // DOF 10 (1-based)
  EXPECT_EQ(s.model.laws[3].attachment.dof(0), 39);  // the free end
  EXPECT_EQ(s.model.structure.loads[0].dof, 39);
  EXPECT_NEAR(s.model.omega, 0.8 * chainFirstFrequency(spec), 1e-15);
  // The closed-form first frequency is that of the assembled chain.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> modes(Eigen::MatrixXd(s.model.structure.stiffness));
  EXPECT_NEAR(std::sqrt(modes.eigenvalues()[0]), chainFirstFrequency(spec), 1e-12);
}

TEST(SceneGenerator, MatrixMarketVariantGivesTheSameModelAndSolution) {
  ChainSceneSpec spec;
  spec.dofs = 12;
  spec.contacts = 3;
  spec.harmonics = 3;
  const auto dir = std::filesystem::temp_directory_path() / ("eqhb_gen_" + std::to_string(::getpid()));
  const Scene inline_scene = parseScene(chainSceneText(spec), "chain.toml");
  const Scene file_scene = loadScene(writeChainMatrixMarketScene(spec, dir.string()));
  std::filesystem::remove_all(dir);
  const auto& a = inline_scene.model.structure;
  const auto& b = file_scene.model.structure;
  EXPECT_EQ(Eigen::MatrixXd(a.stiffness), Eigen::MatrixXd(b.stiffness));
  EXPECT_EQ(Eigen::MatrixXd(a.damping), Eigen::MatrixXd(b.damping));
  EXPECT_EQ(Eigen::MatrixXd(a.mass), Eigen::MatrixXd(b.mass));
  CondensedSystem system(file_scene.model);
  const auto result = makeSolver("dogleg")->solve(system, Eigen::VectorXd::Zero(system.size()), SolverOptions());
  EXPECT_TRUE(result.converged()) << result.summary();
}

TEST(SceneGenerator, ImpossibleSizesNameTheFlag) {
  ChainSceneSpec spec;
  spec.contacts = 200;
  try {
    chainSceneText(spec);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--contacts = 200"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace eqhb
