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

#include "eqhb/solvers/solver.h"

namespace eqhb {

enum class IpoptFormulation { kLeastSquares, kSquare };

// Ipopt's SolverReturn (as int) -> termination.
Termination ipoptTermination(int solver_return);

class IpoptBackend : public Solver {
 public:
  explicit IpoptBackend(IpoptFormulation formulation) : formulation_(formulation) {}
  std::string name() const override {
    return formulation_ == IpoptFormulation::kLeastSquares ? "ipopt-ls" : "ipopt-square";
  }
  std::string description() const override {
    return formulation_ == IpoptFormulation::kLeastSquares
               ? "Ipopt on min 1/2|g|^2 (Gauss-Newton or limited-memory Hessian)"
               : "Ipopt on the feasibility problem g(z) = 0 (equality constraints, zero objective)";
  }

 protected:
  void run(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
           SolverResult& result) override;

 private:
  IpoptFormulation formulation_;
};

}  // namespace eqhb
