// Ipopt (interior point, MUMPS) adapter through its TNLP interface, in two
// formulations of g(z) = 0:
//   kLeastSquares  min ½‖g‖², exact gradient Jᵀg, Hessian Gauss–Newton JᵀJ
//                  (backend option hessian = gauss-newton, default) or
//                  limited-memory quasi-Newton (hessian = limited-memory)
//   kSquare        feasibility: min 0 subject to g(z) = 0, exact constraint
//                  Jacobian, limited-memory Hessian of the Lagrangian
// The residual tolerance, evaluation limit and wall-clock limit are enforced
// from the intermediate callback. The banner is off.
#pragma once

#include "eqhb/solvers/named_solver.h"

namespace eqhb {

enum class IpoptFormulation { kLeastSquares, kSquare };

// Ipopt's SolverReturn (as int) -> termination.
Termination ipoptTermination(int solver_return);

class IpoptBackend : public NamedSolver {
 public:
  explicit IpoptBackend(IpoptFormulation formulation)
      : NamedSolver(formulation == IpoptFormulation::kLeastSquares
                   ? SolverVariant{"ipopt-ls", "Ipopt on min 1/2|g|^2 (Gauss-Newton or limited-memory Hessian)"}
                   : SolverVariant{"ipopt-square",
                                   "Ipopt on the feasibility problem g(z) = 0 (equality constraints, zero objective)"}),
        formulation_(formulation) {}

 protected:
  void run(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
           SolverResult& result) override;

 private:
  IpoptFormulation formulation_;
};

}  // namespace eqhb
