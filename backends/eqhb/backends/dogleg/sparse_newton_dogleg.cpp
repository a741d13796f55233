#include "eqhb/backends/dogleg/sparse_newton_dogleg.h"

#include <Eigen/UmfPackSupport>
#include <cmath>
#include <limits>

#include "eqhb/backends/dogleg/dogleg_strategy.h"

namespace eqhb {

namespace {

using dogleg::StopReason;
using dogleg::TrialStep;

// The sparse step strategy: the Jacobian on the system's pattern, its
// Gauss–Newton step from UMFPACK's LU (a singular J leaves only the gradient
// direction), the Cauchy step from products with J and Jᵀ.
class SparseNewtonStrategy : public dogleg::DoglegStrategy {
 public:
  explicit SparseNewtonStrategy(MonitoredSystem& system)
      : system_(system), jacobian_(system.jacobianPattern()) {
    const Eigen::Index n = system.size();
    for (Eigen::VectorXd* v : {&newton_, &scaled_newton_, &gradient_, &direction_, &image_, &cauchy_, &difference_,
                               &model_residual_})
      v->resize(n);
  }

  bool evaluateJacobian(const Eigen::VectorXd& z, Eigen::VectorXd& g, int iteration, StopReason* stop) override {
    if (!system_.residualAndSparseJacobian(z, g, jacobian_)) {
      *stop = {Termination::kEvaluationFailed, -1, "Jacobian evaluation failed"};
      return false;
    }
    return withinTime("Jacobian evaluation", iteration, stop);
  }

  double jacobianColumnNorm(Eigen::Index j) const override { return jacobian_.col(j).norm(); }

  bool prepareModel(const Eigen::VectorXd& g, const Eigen::VectorXd& diag, int iteration, StopReason* stop) override {
    if (!factorise(iteration, stop)) return false;
    have_newton_ = lu_.info() == Eigen::Success;
    if (have_newton_) {
      newton_ = lu_.solve(g);
      newton_ = -newton_;
      have_newton_ = lu_.info() == Eigen::Success && newton_.allFinite();
    }
    if (!have_newton_) ++singular_;
    scaled_newton_ = diag.cwiseProduct(newton_);
    newton_norm_ = have_newton_ ? scaled_newton_.norm() : 0.0;
    // Steepest descent of ½‖g + J p‖² in scaled variables: −D⁻¹ Jᵀ g.
    gradient_.noalias() = jacobian_.transpose() * g;
    gradient_.array() /= diag.array();
    gradient_norm_ = gradient_.norm();
    cauchy_length_ = std::numeric_limits<double>::infinity();
    if (gradient_norm_ > 0.0) {
      direction_ = -(gradient_ / gradient_norm_);
      image_.noalias() = jacobian_ * direction_.cwiseQuotient(diag);
      const double curvature = image_.norm();
      if (curvature > 0.0) cauchy_length_ = gradient_norm_ / (curvature * curvature);
    }
    if (have_newton_ || gradient_norm_ != 0.0) return true;
    *stop = {Termination::kNotProgressing, 4, "singular Jacobian with zero gradient"};
    return false;
  }

  // Dogleg in scaled variables y = D p inside ‖y‖ <= radius.
  void computeStep(const Eigen::VectorXd& diag, double radius, Eigen::VectorXd& step) override {
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

  double modelResidualNorm(const Eigen::VectorXd& g, const Eigen::VectorXd& step) override {
    model_residual_.noalias() = jacobian_ * step;
    model_residual_ += g;
    return model_residual_.norm();
  }

  // A new iterate takes a new Jacobian; a failed step stays on this model.
  bool keepModel(const TrialStep& trial) override { return !trial.accepted; }

  // The Jacobian's evaluation and each factorisation can take long on a
  // large system: the time limit is checked after each, saying where.
  bool withinTime(const char* stage, int iteration, StopReason* stop) override {
    if (!system_.timeLimitReached()) return true;
    *stop = {Termination::kTimeLimit, 7,
             std::string("time limit reached after the ") + stage + " of iteration " + std::to_string(iteration)};
    return false;
  }

  std::string messagePrefix() const override { return "sparse LU (UMFPACK); "; }

  std::string stoppingNote() const override {
    return singular_ > 0 ? " (" + std::to_string(singular_) + " singular Jacobian(s): gradient steps)" : "";
  }

 private:
  // The symbolic analysis once, on the first Jacobian's values; the numeric
  // factorisation of every Jacobian.
  bool factorise(int iteration, StopReason* stop) {
    if (!analyzed_) {
      lu_.analyzePattern(jacobian_);
      analyzed_ = true;
      if (!withinTime("symbolic factorisation", iteration, stop)) return false;
    }
    lu_.factorize(jacobian_);
    return withinTime("numeric factorisation", iteration, stop);
  }

  MonitoredSystem& system_;
  SparseMatrix jacobian_;
  Eigen::UmfPackLU<SparseMatrix> lu_;
  bool analyzed_ = false, have_newton_ = false;
  int singular_ = 0;
  double newton_norm_ = 0.0, gradient_norm_ = 0.0, cauchy_length_ = 0.0;
  Eigen::VectorXd newton_, scaled_newton_, gradient_, direction_, image_, cauchy_, difference_, model_residual_;
};

}  // namespace

void runSparseNewtonDogleg(MonitoredSystem& system, const Eigen::VectorXd& z0,
                           const SolverOptions& options, const DoglegSettings& settings,
                           SolverResult& result) {
  SparseNewtonStrategy strategy(system);
  dogleg::runTrustRegionLoop(system, z0, options, settings, strategy, result);
}

}  // namespace eqhb
