// NLopt adapter: min ½‖g‖² with gradient Jᵀg for the gradient-based
// algorithms (LD_LBFGS, LD_SLSQP), residual only for the derivative-free
// LN_NEWUOA (small systems: at most 200 unknowns). The residual tolerance is
// NLopt's stopval ½ tol²; max_evaluations is maxeval (objective calls);
// NLopt does not expose iterations, so iterations = objective calls.
// Backend option: initial_step > 0 (derivative-free only, default 1).
// LD_LBFGS takes the sparse Jacobian for large systems (Jᵀg only); SLSQP
// and NEWUOA are dense and refuse systems above their limits below.
#pragma once

#include "eqhb/solvers/named_solver.h"

namespace eqhb {

enum class NloptMethod { kLbfgs, kSlsqp, kNewuoa };

constexpr int kNewuoaMostUnknowns = 200;   // O(n²) model, O(n⁴) work per cycle
constexpr int kSlsqpMostUnknowns = 2000;   // dense n x n BFGS matrix and QP

// nlopt_result (as int) -> termination.
Termination nloptTermination(int code);

class NloptBackend : public NamedSolver {
 public:
  explicit NloptBackend(NloptMethod method);

 protected:
  void run(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
           SolverResult& result) override;

 private:
  NloptMethod method_;
};

}  // namespace eqhb
