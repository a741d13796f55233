// The step strategy of the trust-region dogleg loop (trust_region_loop.h):
// what a model of the residual is made of and how a dogleg step is taken on
// it. The loop owns the iterate, the scaling D, the radius and the stopping
// tests; a strategy owns the Jacobian, its factorisation and the model's
// directions. The strategies: the dense QR (with Broyden updates or a fresh
// Jacobian at every iterate; dense_dogleg_strategy.h), and on an LU of the
// Jacobian (lu_dogleg_strategy.h) the dense one (dense_lu_strategy.h, from
// kDenseLuFromUnknowns, the same two policies) and the sparse one (Newton at
// every iterate; sparse_newton_dogleg.h).
#pragma once

#include <Eigen/Dense>
#include <string>

#include "eqhb/solvers/solver.h"

namespace eqhb::dogleg {

// Why a solve stops: the common termination, the MINPACK-style code (info)
// and the message.
struct StopReason {
  Termination termination = Termination::kConverged;
  int code = 0;
  std::string message;
};

// A step just tried, for the strategy to update its model with.
struct TrialStep {
  const Eigen::VectorXd& step;      // p
  const Eigen::VectorXd& residual;  // g(z + p)
  const Eigen::VectorXd& diag;      // D
  double scaled_norm;               // ‖D p‖
  bool accepted;                    // z moved to z + p
  int consecutive_failures;         // steps in a row with ratio < 0.1, this one included
};

class DoglegStrategy {
 public:
  virtual ~DoglegStrategy() = default;

  // Residual and Jacobian at z, the residual into g; false with the reason
  // when the evaluation fails (or, for strategies that check it, the time
  // runs out). `iteration` is the number of the next step.
  virtual bool evaluateJacobian(const Eigen::VectorXd& z, Eigen::VectorXd& g, int iteration, StopReason* stop) = 0;
  // ‖column j‖ of the Jacobian last evaluated, for the scaling D.
  virtual double jacobianColumnNorm(Eigen::Index j) const = 0;
  // Factorises the model g + J p at the scaling `diag`; false with the reason
  // when no step can be taken on it.
  virtual bool prepareModel(const Eigen::VectorXd& g, const Eigen::VectorXd& diag, int iteration,
                            StopReason* stop) = 0;
  // The dogleg step inside ‖D p‖ <= radius, into `step` (no allocation).
  virtual void computeStep(const Eigen::VectorXd& diag, double radius, Eigen::VectorXd& step) = 0;
  // ‖g + J p‖ on the current model (g: the residual the model was made at).
  virtual double modelResidualNorm(const Eigen::VectorXd& g, const Eigen::VectorXd& step) = 0;
  // After a step and the stopping tests: true to take the next step on this
  // (possibly updated) model, false for a fresh Jacobian.
  virtual bool keepModel(const TrialStep& trial) = 0;

  // False with the reason when the time limit has passed after `stage` of
  // step `iteration`; strategies whose stages can take long check it.
  virtual bool withinTime(const char* /*stage*/, int /*iteration*/, StopReason* /*stop*/) { return true; }
  // Put before every message of the result (which algebra ran).
  virtual std::string messagePrefix() const { return ""; }
  // Put after the messages of the stopping tests (what the model went through).
  virtual std::string stoppingNote() const { return ""; }
};

}  // namespace eqhb::dogleg
