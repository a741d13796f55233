#include "eqhb/backends/dogleg/dense_lu_strategy.h"

#include <cmath>
#include <limits>

namespace eqhb::dogleg {

DenseLuStrategy::DenseLuStrategy(MonitoredSystem& system, JacobianPolicy policy, bool refresh)
    : LuDoglegStrategy(system),
      policy_(policy),
      refresh_(refresh && policy == JacobianPolicy::kBroyden),
      z_(system.size()),
      krylov_step_(refresh_ ? system.size() : 0),
      gmres_(refresh_ ? system.size() : 0, refresh_ ? kMostKrylovVectors : 0),
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
  // The refresh model's J at this very iterate (its GMRES missed, or the
  // step after it was rejected): factorised as it is, not evaluated again.
  const bool refreshed_here = refreshed_at_z_ && z == z_;
  refreshed_at_z_ = false;
  if (refreshed_here) {
    g = g_;
    return true;
  }
  z_ = z;
  if (!system().residualAndJacobian(z, g, jacobian_)) {
    *stop = {Termination::kEvaluationFailed, -1, "Jacobian evaluation failed"};
    return false;
  }
  return withinTime("Jacobian evaluation", iteration, stop);
}

bool DenseLuStrategy::prepareModel(const Eigen::VectorXd& g, const Eigen::VectorXd& diag, int iteration,
                                   StopReason* stop) {
  updates_ = 0;
  krylov_ = false;
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
  // The refresh model's step, solved by refreshModel.
  if (krylov_) {
    newton = krylov_step_;
    return true;
  }
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
  if (refresh_ && trial.accepted) return refreshModel(trial);
  // A rejected step: where the residual is too nonsmooth for Newton's model
  // of it (the damper's contacts near their resonance took 10x the steps of
  // the secant updates on it), the rest of the solve is hybrj's: on a new LU
  // of the refreshed J, or on this LU when its J is still the model's.
  if (refresh_) {
    refresh_ = false;
    if (krylov_) return false;
  }
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

bool DenseLuStrategy::refreshModel(const TrialStep& trial) {
  z_ += trial.step;
  refreshed_at_z_ = system().residualAndJacobian(z_, g_, jacobian_);
  if (!refreshed_at_z_) return false;
  krylov_ = true;
  // GMRES missing its tolerance (or a singular LU kept) is no singular J:
  // a new LU of this one, not gradient steps.
  if (!gmres_.solve(jacobian_, lu_, g_, kKrylovTolerance, krylov_step_)) return false;
  StopReason no_step;
  return computeDirections(g_, trial.diag, &no_step);
}

}  // namespace eqhb::dogleg
