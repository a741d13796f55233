#include "eqhb/solvers/square_system.h"

#include <stdexcept>

namespace eqhb {

const SparseMatrix& SquareSystem::jacobianPattern() {
  const int n = size();
  if (dense_pattern_.rows() != n) {
    dense_pattern_ = Eigen::MatrixXd::Ones(n, n).sparseView();
    dense_pattern_.makeCompressed();
  }
  return dense_pattern_;
}

bool SquareSystem::residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                             Eigen::Ref<Eigen::VectorXd> residual,
                                             SparseMatrix& jacobian) {
  const int n = size();
  if (jacobian.rows() != n || jacobian.cols() != n || jacobian.nonZeros() != n * n)
    throw std::invalid_argument("residualAndSparseJacobian: the matrix lacks the Jacobian pattern");
  dense_jacobian_.resize(n, n);
  const bool ok = residualAndJacobian(z, residual, dense_jacobian_);
  // Column-major with every entry: the values are the dense matrix's.
  Eigen::Map<Eigen::MatrixXd>(jacobian.valuePtr(), n, n) = dense_jacobian_;
  return ok;
}

}  // namespace eqhb
