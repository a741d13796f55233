// The one model interface every solver drives: a square nonlinear system
// g(z) = 0 with a dense (weak) Jacobian and, for large systems, the same
// Jacobian as a sparse matrix whose pattern is fixed at set-up. Evaluations
// report failure (a non-finite value, a domain error) by returning false,
// never by throwing.
#pragma once

#include <Eigen/Dense>
#include <string>

#include "eqhb/sparse_matrix.h"

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

  // The scale s_i of each equation: the size of g_i that stands for a unit
  // relative error in the problem's own units. Solvers see and judge g_i / s_i
  // (solver.h). The default, 1, is the absolute measure.
  virtual void residualScales(Eigen::Ref<Eigen::VectorXd> scales) const { scales.setOnes(); }

  // Asked of a point whose residual is within the tolerance: why it is no
  // solution all the same (a law grossly violated, named), or an empty
  // string when it is one. The default knows no physics to check.
  virtual std::string violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& z) {
    static_cast<void>(z);
    return "";
  }

  // True when the system assembles its Jacobian sparse without ever forming
  // a dense size() x size() matrix. Others get the fallback below, which
  // evaluates densely and copies (every entry in the pattern).
  virtual bool nativeSparseJacobian() const { return false; }
  // The Jacobian's pattern (compressed), the same at every z.
  virtual const SparseMatrix& jacobianPattern();
  // Residual and Jacobian values at z; `jacobian` must hold the pattern of
  // jacobianPattern() (a copy of it): only its values are overwritten.
  virtual bool residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                         Eigen::Ref<Eigen::VectorXd> residual,
                                         SparseMatrix& jacobian);

 private:
  SparseMatrix dense_pattern_;      // fallback: every entry
  Eigen::MatrixXd dense_jacobian_;  // fallback: scratch
};

}  // namespace eqhb
