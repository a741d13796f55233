#include "eqhb/stability/phase_exponential.h"

#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>

namespace eqhb {

PhaseExponential::PhaseExponential(const Eigen::MatrixXd& generator) : generator_(generator) {
  const Eigen::Index d = generator.rows();
  if (d == 0 || !generator.allFinite()) return;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(generator, true);
  if (solver.info() != Eigen::Success) return;
  Eigen::MatrixXd v = solver.pseudoEigenvectors();
  const Eigen::MatrixXd blocks = solver.pseudoEigenvalueMatrix();
  // Columns of unit size (a 2x2 block's pair by one factor, which keeps
  // the block): V's conditioning is then about the eigenvectors' angles,
  // not their lengths.
  for (Eigen::Index i = 0; i < v.cols(); ++i) {
    const bool pair = i + 1 < v.cols() && blocks(i, i + 1) != 0.0;
    const double size = pair ? v.middleCols(i, 2).norm() : v.col(i).norm();
    if (size > 0.0) v.middleCols(i, pair ? 2 : 1) /= size;
    if (pair) ++i;
  }
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(v);
  // rcond() estimates the 1-norm reciprocal condition number of V; a
  // defective A gives a (numerically) singular V.
  if (!(lu.rcond() > kMinimumRcond)) return;
  real_.resize(d);
  imaginary_.setZero(d);
  for (Eigen::Index i = 0; i < d; ++i) {
    real_[i] = blocks(i, i);
    if (i + 1 < d && blocks(i, i + 1) != 0.0) {
      imaginary_[i] = blocks(i, i + 1);  // [a b; −b a]
      real_[i + 1] = blocks(i + 1, i + 1);
      imaginary_[i + 1] = 0.0;
      ++i;
    }
  }
  // The decomposition must reproduce A: a failed or inaccurate Schur step
  // would otherwise pass unnoticed.
  const double scale = generator.lpNorm<Eigen::Infinity>() * v.lpNorm<Eigen::Infinity>();
  if (!((generator * v - v * blocks).lpNorm<Eigen::Infinity>() <= 1e-12 * scale)) return;
  vectors_ = v;
  inverse_ = lu.inverse();
  decomposed_ = true;
}

void PhaseExponential::apply(double tau, Eigen::MatrixXd& phi, Eigen::MatrixXd& scratch) const {
  if (!decomposed_) {
    scratch.noalias() = (generator_ * tau).exp() * phi;
    phi.swap(scratch);
    return;
  }
  // Small generators (friction-1d's 4, beam-damper's 12) multiply faster
  // coefficient by coefficient than through the blocked product's packing.
  const bool small = phi.rows() <= kLazyProductSize;
  if (small) scratch.noalias() = inverse_.lazyProduct(phi);
  else scratch.noalias() = inverse_ * phi;
  scaleModes(tau, scratch);
  if (small) phi.noalias() = vectors_.lazyProduct(scratch);
  else phi.noalias() = vectors_ * scratch;
}

void PhaseExponential::scaleModes(double tau, Eigen::MatrixXd& psi) const {
  const Eigen::Index d = real_.size();
  for (Eigen::Index i = 0; i < d; ++i) {
    const double growth = std::exp(real_[i] * tau);
    if (imaginary_[i] == 0.0) {
      psi.row(i) *= growth;
      continue;
    }
    // exp([a b; −b a] τ) = e^{aτ} [cos bτ  sin bτ; −sin bτ  cos bτ].
    const double c = growth * std::cos(imaginary_[i] * tau), s = growth * std::sin(imaginary_[i] * tau);
    for (Eigen::Index j = 0; j < psi.cols(); ++j) {
      const double x = psi(i, j), y = psi(i + 1, j);
      psi(i, j) = c * x + s * y;
      psi(i + 1, j) = -s * x + c * y;
    }
    ++i;
  }
}

Eigen::MatrixXd PhaseExponential::exponential(double tau) const {
  Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(generator_.rows(), generator_.cols()), scratch;
  apply(tau, phi, scratch);
  return phi;
}

}  // namespace eqhb
