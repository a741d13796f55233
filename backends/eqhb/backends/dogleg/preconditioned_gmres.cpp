#include "eqhb/backends/dogleg/preconditioned_gmres.h"

#include <cmath>

namespace eqhb::dogleg {

PreconditionedGmres::PreconditionedGmres(Eigen::Index n, int most_vectors)
    : most_vectors_(most_vectors),
      basis_(n, most_vectors + 1),
      hessenberg_(most_vectors + 1, most_vectors),
      cosines_(most_vectors),
      sines_(most_vectors),
      rhs_(most_vectors + 1),
      coefficients_(most_vectors),
      residual_(n),
      preconditioned_(n),
      product_(n) {}

bool PreconditionedGmres::solve(const Eigen::MatrixXd& jacobian,
                                const Eigen::PartialPivLU<Eigen::MatrixXd>& preconditioner,
                                const Eigen::VectorXd& b, double tolerance, Eigen::VectorXd& y) {
  last_vectors_ = 0;
  const double b_norm = b.norm();
  y = preconditioner.solve(b);
  if (b_norm == 0.0 || !y.allFinite()) return b_norm == 0.0;
  residual_.noalias() = jacobian * y;
  residual_ = b - residual_;
  const double target = tolerance * b_norm;
  double beta = residual_.norm();
  if (beta <= target) return true;
  basis_.col(0) = residual_ / beta;
  rhs_.setZero();
  rhs_[0] = beta;
  int m = 0;
  double error = beta;
  while (m < most_vectors_ && error > target) {
    // w = J M⁻¹ v_m, orthogonalised against v₁ … v_m (modified Gram–Schmidt).
    preconditioned_ = preconditioner.solve(basis_.col(m));
    product_.noalias() = jacobian * preconditioned_;
    for (int i = 0; i <= m; ++i) {
      hessenberg_(i, m) = basis_.col(i).dot(product_);
      product_ -= hessenberg_(i, m) * basis_.col(i);
    }
    const double next_norm = product_.norm();
    hessenberg_(m + 1, m) = next_norm;
    if (next_norm > 0.0) basis_.col(m + 1) = product_ / next_norm;
    // The earlier rotations on the new column, then the one that zeroes h_{m+1,m}.
    for (int i = 0; i < m; ++i) {
      const double a = hessenberg_(i, m), c = hessenberg_(i + 1, m);
      hessenberg_(i, m) = cosines_[i] * a + sines_[i] * c;
      hessenberg_(i + 1, m) = -sines_[i] * a + cosines_[i] * c;
    }
    const double a = hessenberg_(m, m), c = hessenberg_(m + 1, m);
    const double h = std::sqrt(a * a + c * c);
    cosines_[m] = h > 0.0 ? a / h : 1.0;
    sines_[m] = h > 0.0 ? c / h : 0.0;
    hessenberg_(m, m) = h;
    hessenberg_(m + 1, m) = 0.0;
    rhs_[m + 1] = -sines_[m] * rhs_[m];
    rhs_[m] = cosines_[m] * rhs_[m];
    error = std::abs(rhs_[m + 1]);
    ++m;
    if (next_norm == 0.0) break;  // the Krylov space is invariant: exact
  }
  last_vectors_ = m;
  // Back substitution of the triangular m × m system, then y += M⁻¹ V c.
  for (int i = m - 1; i >= 0; --i) {
    double sum = rhs_[i];
    for (int j = i + 1; j < m; ++j) sum -= hessenberg_(i, j) * coefficients_[j];
    coefficients_[i] = hessenberg_(i, i) != 0.0 ? sum / hessenberg_(i, i) : 0.0;
  }
  residual_.noalias() = basis_.leftCols(m) * coefficients_.head(m);
  preconditioned_ = preconditioner.solve(residual_);
  y += preconditioned_;
  return error <= target && y.allFinite();
}

}  // namespace eqhb::dogleg
