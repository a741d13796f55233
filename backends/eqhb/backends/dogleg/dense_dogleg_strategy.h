// The dense step strategy of the trust-region dogleg: the weak Jacobian's
// Householder QR, J = Q R, with the model ‖Qᵀg + R p‖ and doglegStep on it;
// between Jacobians (policy kBroyden) Broyden rank-one updates of Q R, a
// fresh Jacobian after two failed steps in a row; with kEveryIteration a
// fresh Jacobian at every new iterate.
#pragma once

#include <Eigen/Dense>

#include "eqhb/backends/dogleg/dogleg_strategy.h"
#include "eqhb/backends/dogleg/powell_dogleg.h"

namespace eqhb::dogleg {

class DenseDoglegStrategy : public DoglegStrategy {
 public:
  DenseDoglegStrategy(MonitoredSystem& system, JacobianPolicy policy);

  bool evaluateJacobian(const Eigen::VectorXd& z, Eigen::VectorXd& g, int iteration, StopReason* stop) override;
  double jacobianColumnNorm(Eigen::Index j) const override { return jacobian_.col(j).norm(); }
  bool prepareModel(const Eigen::VectorXd& g, const Eigen::VectorXd& diag, int iteration, StopReason* stop) override;
  void computeStep(const Eigen::VectorXd& diag, double radius, Eigen::VectorXd& step) override;
  double modelResidualNorm(const Eigen::VectorXd& g, const Eigen::VectorXd& step) override;
  bool keepModel(const TrialStep& trial) override;

 private:
  MonitoredSystem& system_;
  JacobianPolicy policy_;
  // Every matrix and vector of the model is made here, once.
  Eigen::MatrixXd jacobian_, q_, r_;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr_;
  Eigen::VectorXd qtf_;             // Qᵀ g
  Eigen::VectorXd model_residual_;  // Qᵀ(g + J p) = qtf + R p of the last step
  Eigen::VectorXd qt_trial_, u_, v_;
  DoglegWorkspace workspace_;
};

}  // namespace eqhb::dogleg
