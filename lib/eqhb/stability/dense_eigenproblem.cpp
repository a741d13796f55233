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
  t_ = h_;
  if (!reduceToSchur()) return false;
  t_ *= scale_;
  const Eigen::MatrixXd& t = t_;
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

// Eigen's RealSchur::computeFromHessenberg without Schur vectors (Eigen
// 3.4, MPL-2.0; the shifts, deflation tests and the order of every operation
// are its own), with the reflections and rotations from the left applied to
// columns up to iu only. A reflection from the left mixes rows within each
// column, and columns right of iu are never read again (iu only decreases),
// so T's columns 0..iu, and with them the eigenvalues, come out bit for bit
// as from the full update. (Cutting the updates from the right to rows from
// il would not be exact: Eigen leaves the small subdiagonal entry at il in
// place, and a later window can reach above it again.)
bool DenseEigenproblem::reduceToSchur() {
  using Vector3 = Eigen::Vector3d;
  Eigen::MatrixXd& t = t_;
  const Eigen::Index size = t.cols();
  workspace_.resize(size);
  double* workspace = workspace_.data();
  const Eigen::Index max_iterations = 40 * size;  // RealSchur's m_maxIterationsPerRow
  double norm = 0.0;  // computeNormOfT
  for (Eigen::Index j = 0; j < size; ++j) norm += t.col(j).segment(0, std::min(size, j + 2)).cwiseAbs().sum();
  const double eps = std::numeric_limits<double>::epsilon();
  const double zero = std::max(norm * eps * eps, std::numeric_limits<double>::min());
  if (norm == 0.0) return true;

  auto findSmallSubdiagEntry = [&](Eigen::Index iu) {
    Eigen::Index res = iu;
    while (res > 0) {
      double s = std::abs(t(res - 1, res - 1)) + std::abs(t(res, res));
      s = std::max(s * eps, zero);
      if (std::abs(t(res, res - 1)) <= s) break;
      res--;
    }
    return res;
  };
  Eigen::Index iu = size - 1, iter = 0, total = 0;
  double exshift = 0.0;
  while (iu >= 0) {
    const Eigen::Index il = findSmallSubdiagEntry(iu);
    if (il == iu) {  // one root
      t(iu, iu) = t(iu, iu) + exshift;
      if (iu > 0) t(iu, iu - 1) = 0.0;
      iu--;
      iter = 0;
      continue;
    }
    if (il == iu - 1) {  // two roots: splitOffTwoRows on the 2 x 2 block
      const double p = 0.5 * (t(iu - 1, iu - 1) - t(iu, iu));
      const double q = p * p + t(iu, iu - 1) * t(iu - 1, iu);
      t(iu, iu) += exshift;
      t(iu - 1, iu - 1) += exshift;
      if (q >= 0.0) {
        const double z = std::sqrt(std::abs(q));
        Eigen::JacobiRotation<double> rot;
        if (p >= 0.0)
          rot.makeGivens(p + z, t(iu, iu - 1));
        else
          rot.makeGivens(p - z, t(iu, iu - 1));
        t.block(0, iu - 1, size, 2).applyOnTheLeft(iu - 1, iu, rot.adjoint());
        t.topRows(iu + 1).applyOnTheRight(iu - 1, iu, rot);
        t(iu, iu - 1) = 0.0;
      }
      if (iu > 1) t(iu - 1, iu - 2) = 0.0;
      iu -= 2;
      iter = 0;
      continue;
    }
    // computeShift
    Vector3 shift(t(iu, iu), t(iu - 1, iu - 1), t(iu, iu - 1) * t(iu - 1, iu));
    if (iter == 10) {  // Wilkinson's ad hoc shift (the whole diagonal, as Eigen)
      exshift += shift(0);
      for (Eigen::Index i = 0; i <= iu; ++i) t(i, i) -= shift(0);
      const double s = std::abs(t(iu, iu - 1)) + std::abs(t(iu - 1, iu - 2));
      shift << 0.75 * s, 0.75 * s, -0.4375 * s * s;
    }
    if (iter == 30) {  // MATLAB's ad hoc shift
      double s = (shift(1) - shift(0)) / 2.0;
      s = s * s + shift(2);
      if (s > 0.0) {
        s = std::sqrt(s);
        if (shift(1) < shift(0)) s = -s;
        s = s + (shift(1) - shift(0)) / 2.0;
        s = shift(0) - shift(2) / s;
        exshift += s;
        for (Eigen::Index i = 0; i <= iu; ++i) t(i, i) -= s;
        shift.setConstant(0.964);
      }
    }
    iter = iter + 1;
    total = total + 1;
    if (total > max_iterations) return false;
    // initFrancisQRStep
    Vector3 first = Vector3::Zero();
    Eigen::Index im;
    for (im = iu - 2; im >= il; --im) {
      const double tmm = t(im, im), r = shift(0) - tmm, s = shift(1) - tmm;
      first(0) = (r * s - shift(2)) / t(im + 1, im) + t(im, im + 1);
      first(1) = t(im + 1, im + 1) - tmm - r - s;
      first(2) = t(im + 2, im + 1);
      if (im == il) break;
      const double lhs = t(im, im - 1) * (std::abs(first(1)) + std::abs(first(2)));
      const double rhs = first(0) * (std::abs(t(im - 1, im - 1)) + std::abs(tmm) + std::abs(t(im + 1, im + 1)));
      if (std::abs(lhs) < eps * rhs) break;
    }
    // performFrancisQRStep, the updates cut to rows and columns il..iu
    for (Eigen::Index k = im; k <= iu - 2; ++k) {
      const bool first_iteration = k == im;
      Vector3 v = first_iteration ? first : Vector3(t.block<3, 1>(k, k - 1));
      double tau, beta;
      Eigen::Vector2d ess;
      v.makeHouseholder(ess, tau, beta);
      if (beta != 0.0) {
        if (first_iteration && k > il)
          t(k, k - 1) = -t(k, k - 1);
        else if (!first_iteration)
          t(k, k - 1) = beta;
        t.block(k, k, 3, iu - k + 1).applyHouseholderOnTheLeft(ess, tau, workspace);
        t.block(0, k, std::min(iu, k + 3) + 1, 3).applyHouseholderOnTheRight(ess, tau, workspace);
      }
    }
    Eigen::Vector2d v = t.block<2, 1>(iu - 1, iu - 2);
    double tau, beta;
    Eigen::Matrix<double, 1, 1> ess;
    v.makeHouseholder(ess, tau, beta);
    if (beta != 0.0) {
      t(iu - 1, iu - 2) = beta;
      t.block(iu - 1, iu - 1, 2, 2).applyHouseholderOnTheLeft(ess, tau, workspace);
      t.block(0, iu - 1, iu + 1, 2).applyHouseholderOnTheRight(ess, tau, workspace);
    }
    for (Eigen::Index i = im + 2; i <= iu; ++i) {  // round-off below the subdiagonal
      t(i, i - 2) = 0.0;
      if (i > im + 2) t(i, i - 3) = 0.0;
    }
  }
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
