// Eigenvalues of a dense real matrix with eigenvectors only where asked.
//
// Eigen's EigenSolver accumulates the Schur vectors during the QR iteration
// (about half of its cost) and then forms every eigenvector. Hill's method
// needs the vectors of the finite eigenvalues only, and for a conjugate pair
// one vector gives both. Here the eigenvalues come from the same computation
// as EigenSolver's without vectors (same scaling, Hessenberg reduction and
// real Schur iteration: bit-identical eigenvalues, in the same order), and
// an eigenvector from one step of inverse iteration on the Hessenberg form H
// (a complex LU of H − λI costs O(m²), H being upper Hessenberg) mapped back
// by the Hessenberg transformation Q: v = Q y. The vectors agree with
// EigenSolver's up to scale and round-off.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <vector>

namespace eqhb {

class DenseEigenproblem {
 public:
  // Eigenvalues of `a` (square); false if the QR iteration did not converge
  // or an eigenvalue is not finite (as EigenSolver's info()).
  bool compute(const Eigen::MatrixXd& a);
  // In EigenSolver's order: a complex pair as (x + iy, x − iy), y > 0.
  const Eigen::VectorXcd& eigenvalues() const { return values_; }
  // The eigenvectors of eigenvalues `which` (indices into eigenvalues()),
  // column c for which[c], each scaled to largest entry 1 in modulus.
  void eigenvectors(const std::vector<int>& which, Eigen::MatrixXcd* vectors);

 private:
  using Complex = std::complex<double>;
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  // y with (H − μI) y ≈ 0 for μ an eigenvalue of H (scaled), largest entry 1.
  void inverseIteration(Complex mu, Eigen::Ref<Eigen::VectorXcd> y);

  Eigen::HessenbergDecomposition<Eigen::MatrixXd> hessenberg_;
  Eigen::RealSchur<Eigen::MatrixXd> schur_;
  Eigen::MatrixXd h_;             // H of a / scale
  double scale_ = 1.0, h_norm_ = 0.0;
  Eigen::VectorXcd values_;
  RowMajor lu_re_, lu_im_;        // the factors of H − μI
  Eigen::VectorXd y_re_, y_im_;   // the iterate
  Eigen::VectorXcd multipliers_;  // of the elimination, per column
  std::vector<char> swapped_;     // rows k and k+1 exchanged at step k
  Eigen::MatrixXd real_imag_;     // [Re Y, Im Y] for one application of Q
};

}  // namespace eqhb
