// What ends a curve early, between two of its points, keeping the points
// already found: a wall-clock limit on the whole curve (sweep's
// curve_time_limit) and a request from outside (the command line's handler
// of SIGINT and SIGTERM). A point under way finishes first: its solves are
// bounded by their own time limit (SolverOptions::time_limit), so a curve
// passes its limit by at most one point's work. The first point is always
// attempted, so a curve stopped early still says where it began.
#pragma once

#include <atomic>
#include <string>

#include "eqhb/solvers/deadline.h"

namespace eqhb {

struct CurveStop {
  Deadline deadline;                             // from the sweep's start; no limit by default
  const std::atomic<bool>* requested = nullptr;  // set asynchronously (a signal handler); null: never

  // Why the curve stops before its next point, "" to go on.
  std::string due() const;
  // Whether a request from outside (not the time limit) stopped it.
  bool wasRequested() const { return requested && requested->load(std::memory_order_relaxed); }
};

}  // namespace eqhb
