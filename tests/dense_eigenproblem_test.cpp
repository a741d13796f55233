#include "eqhb/stability/dense_eigenproblem.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <complex>
#include <vector>

namespace eqhb {
namespace {

using Complex = std::complex<double>;

// A nonsymmetric matrix with real eigenvalues, complex pairs and a cluster:
// the companion-like coupling of a damped chain plus a random part.
Eigen::MatrixXd testMatrix(int m, unsigned seed) {
  std::srand(seed);
  Eigen::MatrixXd a = Eigen::MatrixXd::Random(m, m);
  for (int i = 0; i + 1 < m; i += 2) {  // rotations: complex pairs
    a(i, i + 1) += 3.0 + i;
    a(i + 1, i) -= 3.0 + i;
  }
  return a;
}

TEST(DenseEigenproblem, EigenvaluesAreEigenSolversBitForBit) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Eigen::MatrixXd a = testMatrix(57, seed);
    DenseEigenproblem problem;
    ASSERT_TRUE(problem.compute(a));
    const Eigen::EigenSolver<Eigen::MatrixXd> reference(a, false);
    ASSERT_EQ(problem.eigenvalues().size(), reference.eigenvalues().size());
    for (Eigen::Index j = 0; j < a.rows(); ++j) EXPECT_EQ(problem.eigenvalues()[j], reference.eigenvalues()[j]) << j;
  }
}

TEST(DenseEigenproblem, RequestedVectorsAreEigenvectorsAndMatchEigenSolvers) {
  const Eigen::MatrixXd a = testMatrix(40, 7);
  DenseEigenproblem problem;
  ASSERT_TRUE(problem.compute(a));
  const Eigen::EigenSolver<Eigen::MatrixXd> reference(a, true);
  // Every other eigenvalue, so that some pairs are asked for one member
  // only, in reverse order (the columns follow the request).
  std::vector<int> which;
  for (int j = static_cast<int>(a.rows()) - 1; j >= 0; j -= 2) which.push_back(j);
  which.push_back(0);
  Eigen::MatrixXcd vectors;
  problem.eigenvectors(which, &vectors);
  ASSERT_EQ(vectors.cols(), static_cast<Eigen::Index>(which.size()));
  int complex_values = 0;
  for (size_t c = 0; c < which.size(); ++c) {
    const Complex lambda = problem.eigenvalues()[which[c]];
    complex_values += lambda.imag() != 0.0;
    const Eigen::VectorXcd v = vectors.col(static_cast<Eigen::Index>(c));
    EXPECT_NEAR(v.norm(), 1.0, 1e-12);
    EXPECT_LT((a.cast<Complex>() * v - lambda * v).norm(), 1e-12 * a.norm()) << lambda;
    // The same direction as EigenSolver's vector (they differ by a complex
    // scale): |⟨u, v⟩| = ‖u‖‖v‖.
    const Eigen::VectorXcd u = reference.eigenvectors().col(which[c]);
    EXPECT_NEAR(std::abs(u.dot(v)) / u.norm(), 1.0, 1e-10) << lambda;
  }
  EXPECT_GT(complex_values, 4);  // the conjugate-pair branch is exercised
}

TEST(DenseEigenproblem, ZeroMatrixHasZeroEigenvalues) {
  DenseEigenproblem problem;
  ASSERT_TRUE(problem.compute(Eigen::MatrixXd::Zero(5, 5)));
  EXPECT_EQ(problem.eigenvalues().cwiseAbs().maxCoeff(), 0.0);
  Eigen::MatrixXcd vectors;
  problem.eigenvectors({1, 3}, &vectors);
  EXPECT_EQ(vectors.col(0).norm(), 1.0);
  EXPECT_EQ(vectors.col(1).norm(), 1.0);
}

}  // namespace
}  // namespace eqhb
