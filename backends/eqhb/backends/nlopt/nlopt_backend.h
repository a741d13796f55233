// NLopt adapter: min ½‖g‖² with gradient Jᵀg for the gradient-based
// algorithms (LD_LBFGS, LD_SLSQP), residual only for the derivative-free
// LN_NEWUOA (small systems: at most 200 unknowns). The residual tolerance is
// NLopt's stopval ½ tol²; max_evaluations is maxeval (objective calls);
// NLopt does not expose iterations, so iterations = objective calls.
// Backend option: initial_step > 0 (derivative-free only, default 1).
#pragma once

#include "eqhb/solvers/solver.h"

namespace eqhb {

enum class NloptMethod { kLbfgs, kSlsqp, kNewuoa };

// nlopt_result (as int) -> termination.
Termination nloptTermination(int code);

class NloptBackend : public Solver {
 public:
  explicit NloptBackend(NloptMethod method) : method_(method) {}
  std::string name() const override;
  std::string description() const override;

 protected:
  void run(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
           SolverResult& result) override;

 private:
  NloptMethod method_;
};

}  // namespace eqhb
