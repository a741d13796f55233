// The LU step strategy of the trust-region dogleg (trust_region_loop.h): the
// Gauss–Newton step B p = −g from an LU factorisation of the model matrix B
// (the weak Jacobian, or it with Broyden updates), and the Cauchy step from
// products with B and Bᵀ alone (no Q is formed). By default a fresh Jacobian
// at every new iterate (Newton); what B is stored in, how it is factorised
// and whether it is updated is left to the variants: dense (Eigen's
// partial-pivoting LU, dense_lu_strategy.h) and sparse (UMFPACK,
// sparse_newton_dogleg.h).
#pragma once

#include <Eigen/Dense>
#include <string>

#include "eqhb/backends/dogleg/dogleg_strategy.h"
#include "eqhb/solvers/solver.h"

namespace eqhb::dogleg {

class LuDoglegStrategy : public DoglegStrategy {
 public:
  explicit LuDoglegStrategy(MonitoredSystem& system);

  // Factorises the Jacobian just evaluated, then the directions at g.
  bool prepareModel(const Eigen::VectorXd& g, const Eigen::VectorXd& diag, int iteration, StopReason* stop) override;
  void computeStep(const Eigen::VectorXd& diag, double radius, Eigen::VectorXd& step) override;
  double modelResidualNorm(const Eigen::VectorXd& g, const Eigen::VectorXd& step) override;
  // A new iterate takes a new Jacobian; a failed step stays on this model.
  bool keepModel(const TrialStep& trial) override { return !trial.accepted; }
  // The Jacobian's evaluation and each factorisation can take long on a
  // large system: the time limit is checked after each, saying where.
  bool withinTime(const char* stage, int iteration, StopReason* stop) override;
  std::string stoppingNote() const override;

 protected:
  MonitoredSystem& system() { return system_; }
  // The Gauss–Newton step, the steepest-descent direction and the Cauchy
  // length of the model at g and the scaling diag; false with the reason when
  // B is singular and the gradient zero (no step to take).
  bool computeDirections(const Eigen::VectorXd& g, const Eigen::VectorXd& diag, StopReason* stop);
  // g + B p of the last modelResidualNorm call.
  const Eigen::VectorXd& lastModelResidual() const { return model_residual_; }

 private:
  // The LU of the Jacobian last evaluated; false with the reason when the
  // time runs out (a singular J is not a failure: solveNewton says so).
  virtual bool factorise(int iteration, StopReason* stop) = 0;
  // newton = B⁻¹ g on that LU; false when B is singular.
  virtual bool solveNewton(const Eigen::VectorXd& g, Eigen::VectorXd& newton) = 0;
  virtual void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& bx) = 0;             // B x
  virtual void multiplyTransposed(const Eigen::VectorXd& x, Eigen::VectorXd& btx) = 0;  // Bᵀ x

  MonitoredSystem& system_;
  bool have_newton_ = false;
  int singular_ = 0;
  double newton_norm_ = 0.0, gradient_norm_ = 0.0, cauchy_length_ = 0.0;
  Eigen::VectorXd newton_, scaled_newton_, gradient_, direction_, unscaled_, image_, cauchy_, difference_,
      model_residual_;
};

}  // namespace eqhb::dogleg
