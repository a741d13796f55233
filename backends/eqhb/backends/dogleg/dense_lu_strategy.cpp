#include "eqhb/backends/dogleg/dense_lu_strategy.h"

#include <cmath>
#include <limits>

namespace eqhb::dogleg {

DenseLuStrategy::DenseLuStrategy(MonitoredSystem& system, JacobianPolicy policy)
    : LuDoglegStrategy(system),
      policy_(policy),
      jacobian_(system.size(), system.size()),
      lu_(system.size()),
      g_(system.size()),
      update_u_(system.size()),
      update_v_(system.size()),
      inverse_update_u_(system.size()) {
  if (policy_ != JacobianPolicy::kBroyden) return;
  u_.resize(system.size(), kMostUpdates);
  v_.resize(system.size(), kMostUpdates);
  inverse_u_.resize(system.size(), kMostUpdates);
  inverse_scale_.resize(kMostUpdates);
  coefficients_.resize(kMostUpdates);
}

bool DenseLuStrategy::evaluateJacobian(const Eigen::VectorXd& z, Eigen::VectorXd& g, int iteration,
                                       StopReason* stop) {
  if (!system().residualAndJacobian(z, g, jacobian_)) {
    *stop = {Termination::kEvaluationFailed, -1, "Jacobian evaluation failed"};
    return false;
  }
  return withinTime("Jacobian evaluation", iteration, stop);
}

bool DenseLuStrategy::prepareModel(const Eigen::VectorXd& g, const Eigen::VectorXd& diag, int iteration,
                                   StopReason* stop) {
  updates_ = 0;
  g_ = g;
  return LuDoglegStrategy::prepareModel(g, diag, iteration, stop);
}

bool DenseLuStrategy::factorise(int iteration, StopReason* stop) {
  lu_.compute(jacobian_);
  return withinTime("LU factorisation", iteration, stop);
}

// A singular J has a zero pivot: the solve then has an infinite or NaN
// entry, which computeDirections' finiteness test turns into gradient steps.
bool DenseLuStrategy::solveNewton(const Eigen::VectorXd& g, Eigen::VectorXd& newton) {
  applyInverse(g, newton);
  return true;
}

void DenseLuStrategy::applyInverse(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  y = lu_.solve(x);
  // B_{i+1}⁻¹ = Bᵢ⁻¹ − (Bᵢ⁻¹uᵢ)(vᵢᵀBᵢ⁻¹) / (1 + vᵢᵀBᵢ⁻¹uᵢ).
  for (int i = 0; i < updates_; ++i) y -= (inverse_scale_[i] * v_.col(i).dot(y)) * inverse_u_.col(i);
}

void DenseLuStrategy::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& bx) {
  bx.noalias() = jacobian_ * x;
  if (updates_ == 0) return;
  coefficients_.head(updates_).noalias() = v_.leftCols(updates_).transpose() * x;
  bx.noalias() += u_.leftCols(updates_) * coefficients_.head(updates_);
}

void DenseLuStrategy::multiplyTransposed(const Eigen::VectorXd& x, Eigen::VectorXd& btx) {
  btx.noalias() = jacobian_.transpose() * x;
  if (updates_ == 0) return;
  coefficients_.head(updates_).noalias() = u_.leftCols(updates_).transpose() * x;
  btx.noalias() += v_.leftCols(updates_) * coefficients_.head(updates_);
}

bool DenseLuStrategy::keepModel(const TrialStep& trial) {
  if (policy_ == JacobianPolicy::kEveryIteration) return !trial.accepted;
  if (trial.consecutive_failures == 2 || updates_ == kMostUpdates) return false;
  // Broyden: B⁺ = B + u vᵀ, u = (g⁺ − g − B p)/‖Dp‖, v = D²p/‖Dp‖ (the
  // model's error at the trial, spread along the scaled step).
  update_u_ = (trial.residual - lastModelResidual()) / trial.scaled_norm;
  update_v_ = trial.diag.cwiseProduct(trial.diag.cwiseProduct(trial.step)) / trial.scaled_norm;
  applyInverse(update_u_, inverse_update_u_);
  const double denominator = 1.0 + update_v_.dot(inverse_update_u_);
  // 1 + vᵀB⁻¹u = 0: B⁺ is singular; (near) there the secant model says
  // nothing trustworthy, so the model restarts from a fresh Jacobian.
  if (!(std::abs(denominator) > std::sqrt(std::numeric_limits<double>::epsilon()))) return false;
  u_.col(updates_) = update_u_;
  v_.col(updates_) = update_v_;
  inverse_u_.col(updates_) = inverse_update_u_;
  inverse_scale_[updates_] = 1.0 / denominator;
  ++updates_;
  if (trial.accepted) g_ = trial.residual;
  StopReason no_step;
  return computeDirections(g_, trial.diag, &no_step);
}

}  // namespace eqhb::dogleg
