// MINPACK's hybrj (cminpack) as a reference backend: the same system, the
// same tolerances as the own dogleg, so the two are always measured against
// each other. The residual tolerance and the time limit are enforced from
// the callback (a negative iflag stops hybrj).
//
// Backend options: factor (> 0, default 100), xtol (>= 0, default 1e-14),
// mode ("columns": internal column scaling, MINPACK mode 1; "none": unit D).
// Dense only: refuses systems above kMinpackMostUnknowns and sparse requests.
#pragma once

#include "eqhb/solvers/named_solver.h"

namespace eqhb {

// Above this, hybrj's n x n QR per Jacobian takes minutes.
constexpr int kMinpackMostUnknowns = 3000;

// hybrj's info (and the callback's own negative codes) -> termination.
Termination minpackTermination(int info);
const char* minpackMessage(int info);

class MinpackHybrj : public NamedSolver {
 public:
  MinpackHybrj()
      : NamedSolver({"minpack",
                "MINPACK hybrj (cminpack): Powell hybrid, the reference the own dogleg is measured against"}) {}

 protected:
  void run(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
           SolverResult& result) override;
};

}  // namespace eqhb
