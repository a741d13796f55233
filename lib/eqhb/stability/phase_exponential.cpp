#include "eqhb/stability/phase_exponential.h"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace eqhb {

// ‖(A V − V D) x‖∞ / ‖x‖₂ for a fixed probe x with entries of either sign
// and varied size, D (real_, imaginary_) block diagonal: A (V x) − V (D x),
// O(d²), where the whole A V − V D (a d³ product, a tenth of the
// decomposition's time on the lap joint's 184-square generators) would
// only sharpen the bound by about √d. Rounding leaves ~ε‖A‖‖V‖ per entry;
// a failed Schur step leaves whole columns off, which the probe sees.
double PhaseExponential::reproductionError(const Eigen::MatrixXd& generator, const Eigen::MatrixXd& v) const {
  const Eigen::Index d = v.cols();
  Eigen::VectorXd probe(d), scaled(d);
  for (Eigen::Index j = 0; j < d; ++j) probe[j] = (j % 2 == 0 ? 1.0 : -1.0) * (1.0 + 0.37 * static_cast<double>(j % 5));
  for (Eigen::Index i = 0; i < d; ++i) {
    if (imaginary_[i] == 0.0) {
      scaled[i] = real_[i] * probe[i];
      continue;
    }
    // [a b; −b a]: (D x)_i = a x_i + b x_{i+1}, (D x)_{i+1} = −b x_i + a x_{i+1}.
    const double a = real_[i], b = imaginary_[i];
    scaled[i] = a * probe[i] + b * probe[i + 1];
    scaled[i + 1] = -b * probe[i] + a * probe[i + 1];
    ++i;
  }
  const Eigen::VectorXd residual = generator * (v * probe) - v * scaled;
  return residual.lpNorm<Eigen::Infinity>() / probe.norm();
}

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
  if (!(reproductionError(generator, v) <= 1e-12 * scale)) return;
  // The blocks by decreasing real part, so that the modes a phase leaves
  // are a leading set (a permutation of V's columns: the same product).
  std::vector<Eigen::Index> starts;
  for (Eigen::Index i = 0; i < d; i += imaginary_[i] != 0.0 ? 2 : 1) starts.push_back(i);
  std::stable_sort(starts.begin(), starts.end(),
                   [this](Eigen::Index x, Eigen::Index y) { return real_[x] > real_[y]; });
  const Eigen::MatrixXd inverse = lu.inverse();
  vectors_.resize(d, d);
  inverse_.resize(d, d);  // (V P)⁻¹ = Pᵀ V⁻¹: V⁻¹'s rows likewise
  Eigen::VectorXd real(d), imaginary(d);
  Eigen::Index to = 0;
  for (Eigen::Index from : starts) {
    const Eigen::Index width = imaginary_[from] != 0.0 ? 2 : 1;
    vectors_.middleCols(to, width) = v.middleCols(from, width);
    inverse_.middleRows(to, width) = inverse.middleRows(from, width);
    real.segment(to, width) = real_.segment(from, width);
    imaginary.segment(to, width) = imaginary_.segment(from, width);
    to += width;
  }
  real_.swap(real);
  imaginary_.swap(imaginary);
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

void PhaseExponential::scaleModes(double tau, Eigen::Ref<Eigen::MatrixXd> psi) const {
  const Eigen::Index d = psi.rows();
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

Eigen::Index PhaseExponential::survivingModes(double tau) const {
  const double negligible = std::log(kNegligibleGrowth);
  Eigen::Index kept = 0;
  while (kept < real_.size() && real_[kept] * tau > negligible) ++kept;
  return kept;
}

void PhaseExponential::multipliers(double tau, Eigen::Ref<Eigen::VectorXcd> out) const {
  for (Eigen::Index i = 0; i < real_.size(); ++i) {
    out[i] = std::exp(std::complex<double>(real_[i], imaginary_[i]) * tau);
    if (imaginary_[i] == 0.0) continue;
    out[i + 1] = std::conj(out[i]);  // [a b; −b a]: a ± ib
    ++i;
  }
}

Eigen::MatrixXd PhaseExponential::exponential(double tau) const {
  Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(generator_.rows(), generator_.cols()), scratch;
  apply(tau, phi, scratch);
  return phi;
}

}  // namespace eqhb
