#include "sweep_watch.h"

namespace py = pybind11;

namespace eqhb::python {

namespace {
constexpr double kSignalCheckSeconds = 0.05;
}  // namespace

SweepWatch::SweepWatch(py::object progress) : progress_(std::move(progress)) {}

Progress SweepWatch::callback() {
  return [this](const CurvePoint& point, int index) { watch(point, index); };
}

void SweepWatch::watch(const CurvePoint& point, int index) {
  if (stop_.load(std::memory_order_relaxed)) return;
  const auto now = std::chrono::steady_clock::now();
  if (progress_.is_none() && std::chrono::duration<double>(now - last_check_).count() < kSignalCheckSeconds) return;
  last_check_ = now;
  py::gil_scoped_acquire gil;
  try {
    if (!progress_.is_none()) {
      py::dict seen;
      seen["index"] = index;
      seen["omega"] = point.omega;
      seen["converged"] = point.converged;
      progress_(seen);
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  } catch (py::error_already_set& e) {
    stop_.store(true);
    // Ctrl-C stops the curve like SIGINT on the command line: its points
    // are returned. Anything else is the caller's and is raised again.
    if (!e.matches(PyExc_KeyboardInterrupt)) failure_.emplace(std::move(e));
  }
}

void SweepWatch::raiseIfFailed() {
  if (failure_) {
    py::error_already_set e = std::move(*failure_);
    failure_.reset();
    throw e;
  }
}

}  // namespace eqhb::python
