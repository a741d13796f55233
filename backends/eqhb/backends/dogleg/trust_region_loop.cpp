#include "eqhb/backends/dogleg/trust_region_loop.h"

#include <cmath>
#include <limits>

#include "eqhb/backends/dogleg/trust_radius.h"

namespace eqhb::dogleg {

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

class TrustRegionLoop {
 public:
  TrustRegionLoop(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
                  const DoglegSettings& settings, DoglegStrategy& strategy, SolverResult& result)
      : system_(system), options_(options), settings_(settings), strategy_(strategy), result_(result), z_(z0) {
    // Every vector of the iteration is made here, once.
    const Eigen::Index n = system.size();
    g_.resize(n);
    trial_.resize(n);
    g_trial_.resize(n);
    step_.resize(n);
    diag_ = Eigen::VectorXd::Ones(n);
  }

  void run() {
    result_.solution = z_;
    if (!system_.residual(z_, g_))
      return finish({Termination::kEvaluationFailed, -1, "residual failed at the initial guess"});
    g_norm_ = g_.norm();
    if (g_norm_ <= options_.residual_tolerance)
      return finish({Termination::kConverged, 0, "initial guess within tolerance"});
    StopReason stop;
    if (!strategy_.withinTime("initial residual", result_.iterations + 1, &stop)) return finish(stop);
    while (true) {
      if (!startModel(&stop)) return finish(stop);
      bool fresh_jacobian = true;
      bool keep_model = true;
      while (keep_model) {
        if (iterationLimitReached()) return;
        ++result_.iterations;
        if (!tryStep(&stop)) return finish(stop);
        countSlowProgress(fresh_jacobian);
        if (residualConverged() || trustRadiusTooSmall() || evaluationLimitReached() || timeLimitReached() ||
            stepsBelowPrecision() || jacobiansNotProgressing() || stepsNotProgressing())
          return;
        keep_model = strategy_.keepModel({step_, g_trial_, diag_, step_norm_, accepted_, consecutive_failures_});
        fresh_jacobian = false;
      }
    }
  }

 private:
  // A fresh Jacobian at z, the scaling and (before a first success) the
  // radius it sets, and the strategy's model on it.
  bool startModel(StopReason* stop) {
    if (!strategy_.evaluateJacobian(z_, g_, result_.iterations + 1, stop)) return false;
    g_norm_ = g_.norm();
    // Until a step succeeds, every Jacobian restarts the scaling and the
    // radius from scratch (MINPACK's iter == 1 block): a first model that
    // overshot says nothing about the right radius for the next one.
    if (settings_.scale_columns) {
      for (Eigen::Index j = 0; j < diag_.size(); ++j) {
        const double norm = strategy_.jacobianColumnNorm(j);
        const double scale = norm == 0.0 ? 1.0 : norm;
        diag_[j] = no_success_yet_ ? scale : std::max(diag_[j], scale);
      }
    }
    if (no_success_yet_) {
      z_norm_ = diag_.cwiseProduct(z_).norm();
      radius_ = z_norm_ > 0.0 ? settings_.factor * z_norm_ : settings_.factor;
    }
    return strategy_.prepareModel(g_, diag_, result_.iterations + 1, stop);
  }

  // One dogleg step: the trial point, its reduction ratio, the new radius,
  // and the move to it if it reduced ‖g‖ enough.
  bool tryStep(StopReason* stop) {
    strategy_.computeStep(diag_, radius_, step_);
    step_norm_ = diag_.cwiseProduct(step_).norm();
    // Until a first step succeeds, the radius never exceeds the step taken
    // (MINPACK's iter == 1 rule).
    if (no_success_yet_) radius_ = std::min(radius_, step_norm_);
    trial_ = z_ + step_;
    if (!system_.residual(trial_, g_trial_)) {
      *stop = {Termination::kEvaluationFailed, -1, "residual evaluation failed"};
      return false;
    }
    const double trial_norm = g_trial_.norm();
    actual_ = trial_norm < g_norm_ ? 1.0 - std::pow(trial_norm / g_norm_, 2) : -1.0;
    const double model_norm = strategy_.modelResidualNorm(g_, step_);
    const double predicted = model_norm < g_norm_ ? 1.0 - std::pow(model_norm / g_norm_, 2) : 0.0;
    const double ratio = predicted > 0.0 ? actual_ / predicted : 0.0;
    updateTrustRadius(ratio, step_norm_, radius_, consecutive_successes_);
    consecutive_failures_ = ratio < 0.1 ? consecutive_failures_ + 1 : 0;
    accepted_ = ratio >= 1e-4;
    if (accepted_) {
      no_success_yet_ = false;
      z_ = trial_;
      g_ = g_trial_;
      z_norm_ = diag_.cwiseProduct(z_).norm();
      g_norm_ = trial_norm;
      result_.solution = z_;
    }
    return true;
  }

  // MINPACK's nslow1 / nslow2: steps, and Jacobians, since the last real
  // reduction of ‖g‖².
  void countSlowProgress(bool fresh_jacobian) {
    ++slow_steps_;
    if (actual_ >= 1e-3) slow_steps_ = 0;
    if (fresh_jacobian) ++slow_jacobians_;
    if (actual_ >= 0.1) slow_jacobians_ = 0;
  }

  // ---- stopping tests: each writes the result when it stops the loop.
  bool iterationLimitReached() {
    if (result_.iterations < options_.max_iterations) return false;
    finish({Termination::kIterationLimit, 6, "iteration limit"});
    return true;
  }
  bool residualConverged() {
    return g_norm_ <= options_.residual_tolerance && stopAfterStep(Termination::kConverged, 0, "residual within tolerance");
  }
  bool trustRadiusTooSmall() {
    return (radius_ <= settings_.xtol * z_norm_ || g_norm_ == 0.0) &&
           stopAfterStep(Termination::kStepTolerance, 1, "trust radius below xtol relative to |D z|");
  }
  bool evaluationLimitReached() {
    return system_.evaluationLimitReached() && stopAfterStep(Termination::kEvaluationLimit, 2, "evaluation limit");
  }
  bool timeLimitReached() {
    return system_.timeLimitReached() && stopAfterStep(Termination::kTimeLimit, 7, "time limit");
  }
  bool stepsBelowPrecision() {
    return 0.1 * std::max(0.1 * radius_, step_norm_) <= kEpsilon * z_norm_ &&
           stopAfterStep(Termination::kStepTolerance, 3, "steps below machine precision");
  }
  bool jacobiansNotProgressing() {
    return slow_jacobians_ == 5 &&
           stopAfterStep(Termination::kNotProgressing, 4, "no progress over the last five Jacobian evaluations");
  }
  bool stepsNotProgressing() {
    return slow_steps_ == 10 &&
           stopAfterStep(Termination::kNotProgressing, 5, "no progress over the last ten iterations");
  }

  // A stop after a step: its message with the strategy's note; true.
  bool stopAfterStep(Termination termination, int code, const std::string& message) {
    finish({termination, code, message + strategy_.stoppingNote()});
    return true;
  }

  void finish(const StopReason& stop) {
    result_.termination = stop.termination;
    result_.native_code = stop.code;
    result_.native_message = strategy_.messagePrefix() + stop.message;
    result_.solution = z_;
  }

  MonitoredSystem& system_;
  const SolverOptions& options_;
  const DoglegSettings& settings_;
  DoglegStrategy& strategy_;
  SolverResult& result_;
  Eigen::VectorXd z_, g_, trial_, g_trial_, step_, diag_;
  double g_norm_ = 0.0, z_norm_ = 0.0, radius_ = 0.0, step_norm_ = 0.0, actual_ = 0.0;
  int consecutive_successes_ = 0, consecutive_failures_ = 0, slow_steps_ = 0, slow_jacobians_ = 0;
  bool no_success_yet_ = true, accepted_ = false;
};

}  // namespace

void runTrustRegionLoop(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
                        const DoglegSettings& settings, DoglegStrategy& strategy, SolverResult& result) {
  TrustRegionLoop(system, z0, options, settings, strategy, result).run();
}

}  // namespace eqhb::dogleg
