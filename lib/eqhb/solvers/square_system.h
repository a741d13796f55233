// The one model interface every solver drives: a square nonlinear system
// g(z) = 0 with a dense (weak) Jacobian. Evaluations report failure (a
// non-finite value, a domain error) by returning false, never by throwing.
// A sparse Jacobian can be added as a further virtual with a dense fallback.
#pragma once

#include <Eigen/Dense>

namespace eqhb {

class SquareSystem {
 public:
  virtual ~SquareSystem() = default;
  virtual int size() const = 0;
  // residual.size() == size(). Returns false if the evaluation failed.
  virtual bool residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                        Eigen::Ref<Eigen::VectorXd> residual) = 0;
  // Residual and Jacobian (size() x size(), overwritten) at z.
  virtual bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                   Eigen::Ref<Eigen::VectorXd> residual,
                                   Eigen::Ref<Eigen::MatrixXd> jacobian) = 0;
};

}  // namespace eqhb
