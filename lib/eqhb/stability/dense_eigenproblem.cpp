#include "eqhb/stability/dense_eigenproblem.h"

#include <cmath>
#include <limits>

namespace eqhb {

bool DenseEigenproblem::compute(const Eigen::MatrixXd& a) {
  const Eigen::Index m = a.rows();
  values_.resize(m);
  h_norm_ = 0.0;
  // RealSchur::compute, without the Schur vectors: scale, Hessenberg, QR.
  scale_ = a.cwiseAbs().maxCoeff();
  if (scale_ < std::numeric_limits<double>::min()) {
    values_.setZero();
    h_.setZero(m, m);
    h_norm_ = 0.0;
    return true;
  }
  hessenberg_.compute(a / scale_);
  h_ = hessenberg_.matrixH();
  schur_.computeFromHessenberg(h_, Eigen::MatrixXd(), false);
  if (schur_.info() != Eigen::Success) return false;
  const Eigen::MatrixXd t = schur_.matrixT() * scale_;
  // The eigenvalues from T exactly as EigenSolver::compute reads them.
  for (Eigen::Index i = 0; i < m;) {
    if (i == m - 1 || t(i + 1, i) == 0.0) {
      values_[i] = t(i, i);
      if (!std::isfinite(t(i, i))) return false;
      ++i;
      continue;
    }
    const double p = 0.5 * (t(i, i) - t(i + 1, i + 1));
    const double maxval = std::max(std::abs(p), std::max(std::abs(t(i + 1, i)), std::abs(t(i, i + 1))));
    const double t0 = t(i + 1, i) / maxval, t1 = t(i, i + 1) / maxval, p0 = p / maxval;
    const double z = maxval * std::sqrt(std::abs(p0 * p0 + t0 * t1));
    values_[i] = Complex(t(i + 1, i + 1) + p, z);
    values_[i + 1] = Complex(t(i + 1, i + 1) + p, -z);
    if (!(std::isfinite(values_[i].real()) && std::isfinite(z))) return false;
    i += 2;
  }
  // ‖H‖₁, for the size of a pivot that counts as zero
  for (Eigen::Index j = 0; j < m; ++j) h_norm_ = std::max(h_norm_, h_.col(j).cwiseAbs().sum());
  return true;
}

void DenseEigenproblem::inverseIteration(Complex mu, Eigen::Ref<Eigen::VectorXcd> y) {
  const Eigen::Index m = h_.rows();
  // A pivot below ε‖H‖ (μ is an eigenvalue to working accuracy) is replaced
  // by ε‖H‖, as LAPACK's dlaein does: the solve then grows the eigenvector.
  const double tiny = std::numeric_limits<double>::epsilon() * std::max(h_norm_, 1e-300);
  // Real and imaginary parts in separate row-major planes, the arithmetic
  // written out: loops the compiler vectorises, no complex-multiply calls;
  // a real μ leaves the imaginary plane zero and skips it.
  const bool complex = mu.imag() != 0.0;
  lu_re_.resize(m, m);
  lu_im_.resize(m, m);
  multipliers_.resize(m);
  swapped_.assign(m, 0);
  for (Eigen::Index i = 0; i < m; ++i) {
    const Eigen::Index first = std::max<Eigen::Index>(i - 1, 0);
    for (Eigen::Index j = first; j < m; ++j) lu_re_(i, j) = h_(i, j);
    for (Eigen::Index j = first; j < m; ++j) lu_im_(i, j) = 0.0;
    lu_re_(i, i) -= mu.real();
    lu_im_(i, i) -= mu.imag();
  }
  // |re| + |im|: the pivot sizes as LAPACK's complex routines compare them
  // (no hypot per step).
  auto size = [&](Eigen::Index i, Eigen::Index j) { return std::abs(lu_re_(i, j)) + std::abs(lu_im_(i, j)); };
  // a / b written out (Smith's division, no library call).
  auto divide = [](double ar, double ai, double br, double bi) {
    if (std::abs(br) >= std::abs(bi)) {
      const double r = bi / br, d = br + bi * r;
      return Complex((ar + ai * r) / d, (ai - ar * r) / d);
    }
    const double r = br / bi, d = bi + br * r;
    return Complex((ar * r + ai) / d, (ai * r - ar) / d);
  };
  // Gaussian elimination with partial pivoting: in column k only row k + 1
  // is below the diagonal.
  for (Eigen::Index k = 0; k + 1 < m; ++k) {
    if (size(k + 1, k) > size(k, k)) {
      swapped_[k] = 1;
      lu_re_.row(k).tail(m - k).swap(lu_re_.row(k + 1).tail(m - k));
      if (complex) lu_im_.row(k).tail(m - k).swap(lu_im_.row(k + 1).tail(m - k));
    }
    if (size(k, k) < tiny) lu_re_(k, k) = tiny, lu_im_(k, k) = 0.0;
    const Complex l = divide(lu_re_(k + 1, k), lu_im_(k + 1, k), lu_re_(k, k), lu_im_(k, k));
    multipliers_[k] = l;
    lu_re_(k + 1, k) = lu_im_(k + 1, k) = 0.0;
    const double lr = l.real(), li = l.imag();
    double* __restrict__ re1 = &lu_re_(k + 1, 0);
    double* __restrict__ im1 = &lu_im_(k + 1, 0);
    const double* __restrict__ re0 = &lu_re_(k, 0);
    const double* __restrict__ im0 = &lu_im_(k, 0);
    if (complex) {
      for (Eigen::Index j = k + 1; j < m; ++j) {
        re1[j] -= lr * re0[j] - li * im0[j];
        im1[j] -= lr * im0[j] + li * re0[j];
      }
    } else {
      for (Eigen::Index j = k + 1; j < m; ++j) re1[j] -= lr * re0[j];
    }
  }
  if (size(m - 1, m - 1) < tiny) lu_re_(m - 1, m - 1) = tiny, lu_im_(m - 1, m - 1) = 0.0;
  y_re_.resize(m);
  y_im_.resize(m);
  // U x = y in place; returns ‖x‖₁.
  auto backSubstitute = [&] {
    double norm = 0.0;
    for (Eigen::Index i = m - 1; i >= 0; --i) {
      const double* __restrict__ re = &lu_re_(i, 0);
      const double* __restrict__ im = &lu_im_(i, 0);
      double sum_re = y_re_[i], sum_im = y_im_[i];
      if (complex) {
        for (Eigen::Index j = i + 1; j < m; ++j) {
          sum_re -= re[j] * y_re_[j] - im[j] * y_im_[j];
          sum_im -= re[j] * y_im_[j] + im[j] * y_re_[j];
        }
        const Complex x = divide(sum_re, sum_im, re[i], im[i]);
        y_re_[i] = x.real();
        y_im_[i] = x.imag();
      } else {
        for (Eigen::Index j = i + 1; j < m; ++j) sum_re -= re[j] * y_re_[j];
        y_re_[i] = sum_re / re[i];
      }
      norm += std::abs(y_re_[i]) + std::abs(y_im_[i]);
    }
    return norm;
  };
  // LAPACK's dlaein: the start vector (ones) taken as L⁻¹ of some vector, so
  // U alone, and the solve repeated with the full (LU)⁻¹ until the iterate
  // has grown enough (‖x‖₁ ≥ 0.1/(√m ε‖H‖) for a unit start): one solve in
  // practice, the rest for a nearly defective eigenvalue.
  const double grown = 0.1 / (std::sqrt(static_cast<double>(m)) * tiny);
  y_re_.setOnes();
  y_im_.setZero();
  for (int solve = 0; solve < 3; ++solve) {
    if (solve > 0) {
      const double scale = std::max(y_re_.cwiseAbs().maxCoeff(), y_im_.cwiseAbs().maxCoeff());
      y_re_ /= scale;
      y_im_ /= scale;
      for (Eigen::Index k = 0; k + 1 < m; ++k) {
        if (swapped_[k]) std::swap(y_re_[k], y_re_[k + 1]), std::swap(y_im_[k], y_im_[k + 1]);
        const Complex l = multipliers_[k];
        y_re_[k + 1] -= l.real() * y_re_[k] - l.imag() * y_im_[k];
        y_im_[k + 1] -= l.real() * y_im_[k] + l.imag() * y_re_[k];
      }
    }
    if (backSubstitute() >= grown) break;
  }
  const double norm = std::sqrt(y_re_.squaredNorm() + y_im_.squaredNorm());
  y.real() = y_re_ / norm;
  y.imag() = y_im_ / norm;
}

void DenseEigenproblem::eigenvectors(const std::vector<int>& which, Eigen::MatrixXcd* vectors) {
  const Eigen::Index m = values_.size();
  vectors->resize(m, static_cast<Eigen::Index>(which.size()));
  if (h_norm_ == 0.0) {  // the zero matrix: any vector is an eigenvector
    vectors->setZero();
    for (size_t c = 0; c < which.size(); ++c) (*vectors)(which[c], static_cast<Eigen::Index>(c)) = 1.0;
    return;
  }
  // One inverse iteration per conjugate pair: the x − iy member (second of
  // the pair) takes the conjugate of the x + iy one's vector.
  std::vector<int> representative(which.size()), solved;
  std::vector<int> column_of(m, -1);
  for (size_t c = 0; c < which.size(); ++c) {
    int j = which[c];
    if (values_[j].imag() < 0.0 && j > 0 && values_[j - 1] == std::conj(values_[j])) --j;
    if (column_of[j] < 0) {
      column_of[j] = static_cast<int>(solved.size());
      solved.push_back(j);
    }
    representative[c] = column_of[j];
  }
  const Eigen::Index k = static_cast<Eigen::Index>(solved.size());
  Eigen::VectorXcd y(m);
  real_imag_.resize(m, 2 * k);
  for (Eigen::Index c = 0; c < k; ++c) {
    inverseIteration(values_[solved[c]] / scale_, y);
    real_imag_.col(c) = y.real();
    real_imag_.col(k + c) = y.imag();
  }
  real_imag_.applyOnTheLeft(hessenberg_.matrixQ());  // v = Q y
  for (size_t c = 0; c < which.size(); ++c) {
    const int r = representative[c];
    const double sign = values_[which[c]].imag() < 0.0 && values_[solved[r]].imag() > 0.0 ? -1.0 : 1.0;
    vectors->col(static_cast<Eigen::Index>(c)).real() = real_imag_.col(r);
    vectors->col(static_cast<Eigen::Index>(c)).imag() = sign * real_imag_.col(k + r);
  }
}

}  // namespace eqhb
