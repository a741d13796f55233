// Ceres Solver trust-region adapter: the square system as the least-squares
// problem min ½‖g(z)‖² with the analytic (weak) Jacobian. Dense path: one
// parameter block (a dense Jacobian). Sparse path: one block per unknown and
// per equation, so that Ceres sees the Jacobian's pattern, factored by
// SPARSE_NORMAL_CHOLESKY on SuiteSparse. Strategies: Levenberg–Marquardt,
// traditional dogleg, subspace dogleg.
//
// The residual tolerance, the evaluation limit and the time limit are
// enforced from an iteration callback (Ceres has no absolute ‖g‖ test).
// Backend options: linear_solver = dense_qr (default) | dense_normal_cholesky
// | sparse_normal_cholesky (SuiteSparse; the only one on the sparse path),
// threads >= 1 (default 1).
#pragma once

#include "eqhb/solvers/named_solver.h"

namespace eqhb {

enum class CeresStrategy { kLevenbergMarquardt, kDogleg, kSubspaceDogleg };

// Ceres' TerminationType (as int, so the header needs no Ceres include) ->
// termination.
Termination ceresTermination(int termination_type);

class CeresBackend : public NamedSolver {
 public:
  explicit CeresBackend(CeresStrategy strategy);

 protected:
  void run(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
           SolverResult& result) override;

 private:
  CeresStrategy strategy_;
};

}  // namespace eqhb
