// A sweep run from Python, watched between two of its points (the sweep runs
// without the GIL; the watch takes it briefly):
//  - Ctrl-C: Python's SIGINT handler only marks the signal; the watch runs
//    the pending handlers (PyErr_CheckSignals) and on KeyboardInterrupt
//    stops the curve there, keeping its points, as SIGINT does on the
//    command line (the stop reason says so);
//  - progress: a callable told of each point, {"index", "omega",
//    "converged"}; an exception it raises stops the curve and is raised
//    again once the sweep has returned.
// Without a callable the signals are checked at most every 50 ms, so that a
// fast sweep does not take the GIL at every point.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <optional>

#include "eqhb/continuation/continuation.h"

namespace eqhb::python {

class SweepWatch {
 public:
  explicit SweepWatch(pybind11::object progress);
  // What the sweep sets its stop_requested to.
  const std::atomic<bool>* stopRequested() const { return &stop_; }
  // The sweep's per-point callback: called without the GIL.
  Progress callback();
  // After the sweep, with the GIL: raises what the callable raised.
  void raiseIfFailed();

 private:
  void watch(const CurvePoint& point, int index);

  pybind11::object progress_;  // None: signals only
  std::atomic<bool> stop_{false};
  std::optional<pybind11::error_already_set> failure_;
  std::chrono::steady_clock::time_point last_check_ = std::chrono::steady_clock::now();
};

}  // namespace eqhb::python
