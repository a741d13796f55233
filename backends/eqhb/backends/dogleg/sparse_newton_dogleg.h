// The sparse variant of the own Newton–dogleg: the same scaled trust-region
// dogleg as PowellDogleg with the weak Jacobian at every iterate, but the
// Jacobian stays sparse (the system's fixed pattern) and the Gauss–Newton
// step J p = −g comes from UMFPACK's sparse LU (Davis, "Algorithm 832:
// UMFPACK V4.3", ACM TOMS 30(2), 2004), whose symbolic analysis is made once
// per solve and reused by every numerical factorisation. The Cauchy step
// needs only products with J and Jᵀ. No dense n x n matrix is formed. The
// loop is trust_region_loop.h's; this file is its sparse step strategy.
#pragma once

#include "eqhb/backends/dogleg/trust_region_loop.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// Runs the sparse Newton–dogleg; fills result as Solver::run does.
void runSparseNewtonDogleg(MonitoredSystem& system, const Eigen::VectorXd& z0,
                           const SolverOptions& options, const DoglegSettings& settings,
                           SolverResult& result);

}  // namespace eqhb
