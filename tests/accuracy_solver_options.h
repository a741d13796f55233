// The solver settings of the accuracy tests: residuals at 1e-10 so that the
// errors measured (1e-4 and below) are the discretisation's, not the solve's.
#pragma once

#include "eqhb/solvers/solver.h"

namespace eqhb::test {

inline SolverOptions tightOptions() {
  SolverOptions options;
  options.residual_tolerance = 1e-10;
  options.max_iterations = 400;
  return options;
}

}  // namespace eqhb::test
