// A backbone's solves share one Deadline: each gets the solver's options
// with its time limit cut to what the backbone has left.
#pragma once

#include <algorithm>

#include "eqhb/solvers/deadline.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// `options` with time_limit lowered to the deadline's remaining time (at
// least 1 ms, so that a solve started just before the limit still returns
// a result); unchanged without a limit.
inline SolverOptions withinDeadline(SolverOptions options, const Deadline& deadline) {
  if (deadline.limited()) {
    const double left = std::max(deadline.remaining(), 1e-3);
    options.time_limit = options.time_limit > 0.0 ? std::min(options.time_limit, left) : left;
  }
  return options;
}

}  // namespace eqhb
