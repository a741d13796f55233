#include "eqhb/backends/dogleg/dense_dogleg_strategy.h"

namespace eqhb::dogleg {

DenseDoglegStrategy::DenseDoglegStrategy(MonitoredSystem& system, JacobianPolicy policy)
    : system_(system),
      policy_(policy),
      jacobian_(system.size(), system.size()),
      q_(system.size(), system.size()),
      r_(system.size(), system.size()),
      qr_(system.size(), system.size()),
      qtf_(system.size()),
      model_residual_(system.size()),
      qt_trial_(system.size()),
      u_(system.size()),
      v_(system.size()),
      workspace_(system.size()) {}

bool DenseDoglegStrategy::evaluateJacobian(const Eigen::VectorXd& z, Eigen::VectorXd& g, int /*iteration*/,
                                           StopReason* stop) {
  if (system_.residualAndJacobian(z, g, jacobian_)) return true;
  *stop = {Termination::kEvaluationFailed, -1, "Jacobian evaluation failed"};
  return false;
}

bool DenseDoglegStrategy::prepareModel(const Eigen::VectorXd& g, const Eigen::VectorXd& /*diag*/, int /*iteration*/,
                                       StopReason* /*stop*/) {
  qr_.compute(jacobian_);
  q_ = qr_.householderQ();
  r_ = qr_.matrixQR().triangularView<Eigen::Upper>();
  qtf_.noalias() = q_.transpose() * g;
  return true;
}

void DenseDoglegStrategy::computeStep(const Eigen::VectorXd& diag, double radius, Eigen::VectorXd& step) {
  doglegStep(r_, diag, qtf_, radius, workspace_, step);
}

double DenseDoglegStrategy::modelResidualNorm(const Eigen::VectorXd& /*g*/, const Eigen::VectorXd& step) {
  model_residual_.noalias() = r_ * step;  // Qᵀ(g + J p) = qtf + R p
  model_residual_ += qtf_;
  return model_residual_.norm();
}

bool DenseDoglegStrategy::keepModel(const TrialStep& trial) {
  // Newton–dogleg: a new iterate takes a new weak Jacobian; a failed step
  // stays at the same point on the same exact model with a smaller radius.
  if (policy_ == JacobianPolicy::kEveryIteration) return !trial.accepted;
  if (trial.consecutive_failures == 2) return false;
  // Broyden update of Q R: J⁺ = J + (g⁺ − g − J p)(D²p)ᵀ / ‖Dp‖², in
  // the rotated frame Rᵀ-side u = (Qᵀg⁺ − Qᵀg − R p)/‖Dp‖.
  qt_trial_.noalias() = q_.transpose() * trial.residual;
  u_ = (qt_trial_ - model_residual_) / trial.scaled_norm;
  v_ = trial.diag.cwiseProduct(trial.diag.cwiseProduct(trial.step)) / trial.scaled_norm;
  if (trial.accepted) qtf_ = qt_trial_;
  rankOneUpdate(q_, r_, qtf_, u_, v_);
  return true;
}

}  // namespace eqhb::dogleg
