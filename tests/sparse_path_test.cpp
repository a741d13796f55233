// The sparse path gives what the dense path gives: residual, Jacobian and
// solution on every shipped scene and every form of its laws; the sparse
// Jacobian against finite differences; backends that stay dense refuse.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "registry.h"
#include "test_support.h"

namespace eqhb {
namespace {

std::vector<std::string> shippedScenes() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(EQHB_PROBLEMS_DIR))
    if (entry.path().extension() == ".toml") files.push_back(entry.path().filename().string());
  std::sort(files.begin(), files.end());
  return files;
}

// Every scene once per form its laws accept (the scene's own form when none).
std::vector<std::pair<std::string, Scene>> everySceneAndForm() {
  std::vector<std::pair<std::string, Scene>> all;
  for (const auto& file : shippedScenes()) {
    const Scene scene = loadScene(test::problem(file));
    std::set<std::string> forms;
    for (const auto& attached : scene.model.laws)
      for (const auto& form : lawForms(attached.law->type())) forms.insert(form);
    if (forms.empty()) all.emplace_back(file, scene);
    for (const auto& form : forms)
      all.emplace_back(file + " form " + form,
                       loadScene(test::problem(file), lawOverrides(scene.model, "form", form)));
  }
  return all;
}

Eigen::MatrixXd toDense(const SparseMatrix& m) { return Eigen::MatrixXd(m); }

TEST(SparsePath, FullSystemSparseJacobianEqualsTheDenseOneOnEveryScene) {
  const auto scenes = everySceneAndForm();
  ASSERT_GE(scenes.size(), 7u);
  for (const auto& [label, scene] : scenes) {
    FullSystem system(scene.model);
    ASSERT_TRUE(system.nativeSparseJacobian());
    const int n = system.size();
    // A point with every law active: random but reproducible.
    std::srand(7);
    const Eigen::VectorXd z = Eigen::VectorXd::Random(n);
    Eigen::VectorXd g_dense(n), g_sparse(n);
    Eigen::MatrixXd dense(n, n);
    SparseMatrix sparse = system.jacobianPattern();
    ASSERT_TRUE(system.residualAndJacobian(z, g_dense, dense)) << label;
    ASSERT_TRUE(system.residualAndSparseJacobian(z, g_sparse, sparse)) << label;
    EXPECT_LE((g_dense - g_sparse).norm(), 1e-12 * (1.0 + g_dense.norm())) << label;
    EXPECT_LE((dense - toDense(sparse)).norm(), 1e-12 * (1.0 + dense.norm())) << label;
    // Entries outside the pattern are zero in the dense Jacobian.
    Eigen::MatrixXd outside = dense;
    for (int j = 0; j < n; ++j)
      for (SparseMatrix::InnerIterator it(sparse, j); it; ++it) outside(it.row(), j) = 0.0;
    EXPECT_EQ(outside.norm(), 0.0) << label;
    // Sparse, not a disguised dense matrix.
    EXPECT_LT(sparse.nonZeros(), n * n) << label;
  }
}

TEST(SparsePath, SparseJacobianMatchesFiniteDifferences) {
  // Smooth laws only: finite differences of the nonsmooth forms depend on
  // the side of the kink.
  for (const char* file : {"cubic.toml", "friction-2d.toml", "contact.toml"}) {
    const Scene scene = loadScene(test::problem(file));
    FullSystem system(scene.model);
    const int n = system.size();
    std::srand(11);
    const Eigen::VectorXd z = 0.5 * Eigen::VectorXd::Random(n);
    Eigen::VectorXd g(n);
    SparseMatrix sparse = system.jacobianPattern();
    ASSERT_TRUE(system.residualAndSparseJacobian(z, g, sparse));
    const Eigen::MatrixXd fd = test::finiteDifferenceJacobian(system, z, 1e-6);
    EXPECT_LE((fd - toDense(sparse)).norm(), 1e-5 * (1.0 + fd.norm())) << file;
  }
}

TEST(SparsePath, ChangingOmegaKeepsThePatternAndMovesTheValues) {
  const Scene scene = loadScene(test::problem("friction-2d.toml"));
  FullSystem system(scene.model);
  const SparseMatrix before = system.jacobianPattern();
  const int n = system.size();
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(n, 0.1);
  Eigen::VectorXd g(n);
  SparseMatrix j1 = before, j2 = before;
  system.residualAndSparseJacobian(z, g, j1);
  system.setOmega(1.3 * scene.model.omega);
  system.residualAndSparseJacobian(z, g, j2);
  const SparseMatrix& after = system.jacobianPattern();
  ASSERT_EQ(after.nonZeros(), before.nonZeros());
  EXPECT_TRUE(std::equal(after.innerIndexPtr(), after.innerIndexPtr() + after.nonZeros(),
                         before.innerIndexPtr()));
  EXPECT_GT((toDense(j1) - toDense(j2)).norm(), 1e-3);
  Eigen::MatrixXd dense(n, n);
  system.residualAndJacobian(z, g, dense);
  EXPECT_LE((dense - toDense(j2)).norm(), 1e-12 * dense.norm());
}

TEST(SparsePath, SparseAndDenseOwnSolverGiveTheSameSolutionOnEveryScene) {
  for (const auto& [label, scene] : everySceneAndForm()) {
    for (bool condensed : {false, true}) {
      auto system = makeHbSystem(scene.model, condensed);
      SolverOptions dense_options, sparse_options;
      dense_options.linear_algebra = LinearAlgebra::kDense;
      sparse_options.linear_algebra = LinearAlgebra::kSparse;
      const Eigen::VectorXd z0 = Eigen::VectorXd::Zero(system->size());
      const SolverResult dense = makeSolver("dogleg-newton")->solve(*system, z0, dense_options);
      const SolverResult sparse = makeSolver("dogleg-newton")->solve(*system, z0, sparse_options);
      const std::string what = label + (condensed ? " condensed" : " full");
      if (!dense.converged()) continue;  // a scene the own dogleg does not solve from 0
      ASSERT_TRUE(sparse.converged()) << what << ": " << sparse.summary();
      EXPECT_NE(sparse.native_message.find("sparse LU"), std::string::npos) << what;
      EXPECT_LE((dense.solution - sparse.solution).norm(), 1e-10 * (1.0 + dense.solution.norm()))
          << what;
    }
  }
}

TEST(SparsePath, AutomaticChoiceFollowsTheSize) {
  HbModel small = test::chainWithFriction(7.2, CoulombForm::kMinMax, 5, 0.4);
  FullSystem small_system(small);
  SolverOptions options;
  EXPECT_FALSE(useSparseAlgebra(small_system, options));
  HbModel large = test::chainWithFriction(7.2, CoulombForm::kMinMax, 200, 0.4, 1024);
  FullSystem large_system(large);
  ASSERT_GE(large_system.size(), kSparseFromUnknowns);
  EXPECT_TRUE(useSparseAlgebra(large_system, options));
  options.linear_algebra = LinearAlgebra::kDense;
  EXPECT_FALSE(useSparseAlgebra(large_system, options));
  options.linear_algebra = LinearAlgebra::kSparse;
  EXPECT_TRUE(useSparseAlgebra(small_system, options));
}

}  // namespace
}  // namespace eqhb
