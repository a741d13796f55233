#include "eqhb/backends/dogleg/lu_dogleg_strategy.h"

#include <cmath>
#include <limits>

namespace eqhb::dogleg {

LuDoglegStrategy::LuDoglegStrategy(MonitoredSystem& system) : system_(system) {
  const Eigen::Index n = system.size();
  for (Eigen::VectorXd* v : {&newton_, &scaled_newton_, &gradient_, &direction_, &unscaled_, &image_, &cauchy_,
                             &difference_, &model_residual_})
    v->resize(n);
}

bool LuDoglegStrategy::prepareModel(const Eigen::VectorXd& g, const Eigen::VectorXd& diag, int iteration,
                                        StopReason* stop) {
  return factorise(iteration, stop) && computeDirections(g, diag, stop);
}

bool LuDoglegStrategy::computeDirections(const Eigen::VectorXd& g, const Eigen::VectorXd& diag,
                                             StopReason* stop) {
  have_newton_ = solveNewton(g, newton_);
  if (have_newton_) {
    newton_ = -newton_;
    have_newton_ = newton_.allFinite();
  }
  if (!have_newton_) ++singular_;
  scaled_newton_ = diag.cwiseProduct(newton_);
  newton_norm_ = have_newton_ ? scaled_newton_.norm() : 0.0;
  // Steepest descent of ½‖g + J p‖² in scaled variables: −D⁻¹ Jᵀ g.
  multiplyTransposed(g, gradient_);
  gradient_.array() /= diag.array();
  gradient_norm_ = gradient_.norm();
  cauchy_length_ = std::numeric_limits<double>::infinity();
  if (gradient_norm_ > 0.0) {
    direction_ = -(gradient_ / gradient_norm_);
    unscaled_ = direction_.cwiseQuotient(diag);
    multiply(unscaled_, image_);
    const double curvature = image_.norm();
    if (curvature > 0.0) cauchy_length_ = gradient_norm_ / (curvature * curvature);
  }
  if (have_newton_ || gradient_norm_ != 0.0) return true;
  *stop = {Termination::kNotProgressing, 4, "singular Jacobian with zero gradient"};
  return false;
}

// Dogleg in scaled variables y = D p inside ‖y‖ <= radius.
void LuDoglegStrategy::computeStep(const Eigen::VectorXd& diag, double radius, Eigen::VectorXd& step) {
  if (have_newton_ && newton_norm_ <= radius) {
    step = newton_;
  } else if (gradient_norm_ == 0.0) {
    step = newton_ * (radius / newton_norm_);
  } else if (!have_newton_ || cauchy_length_ >= radius) {
    step = (std::min(radius, cauchy_length_) * direction_).cwiseQuotient(diag);
  } else {
    cauchy_ = cauchy_length_ * direction_;
    difference_ = scaled_newton_ - cauchy_;
    const double a = difference_.squaredNorm();
    const double b = cauchy_.dot(difference_);
    const double c = cauchy_.squaredNorm() - radius * radius;  // < 0
    const double root = std::sqrt(b * b - a * c);
    const double tau = b > 0.0 ? -c / (b + root) : (root - b) / a;
    step = (cauchy_ + tau * difference_).cwiseQuotient(diag);
  }
}

double LuDoglegStrategy::modelResidualNorm(const Eigen::VectorXd& g, const Eigen::VectorXd& step) {
  multiply(step, model_residual_);
  model_residual_ += g;
  return model_residual_.norm();
}

bool LuDoglegStrategy::withinTime(const char* stage, int iteration, StopReason* stop) {
  if (!system_.timeLimitReached()) return true;
  *stop = {Termination::kTimeLimit, 7,
           std::string("time limit reached after the ") + stage + " of iteration " + std::to_string(iteration)};
  return false;
}

std::string LuDoglegStrategy::stoppingNote() const {
  return singular_ > 0 ? " (" + std::to_string(singular_) + " singular Jacobian(s): gradient steps)" : "";
}

}  // namespace eqhb::dogleg
