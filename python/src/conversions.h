// Results as plain Python: numpy arrays for everything sampled or indexed by
// harmonic, dicts for the rest.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "eqhb/continuation/continuation.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/references/time_integrator.h"
#include "eqhb/solvers/solver.h"

namespace eqhb::python {

namespace py = pybind11;

py::array_t<double> toArray(const Eigen::VectorXd& v);
// Row-major copy of a matrix.
py::array_t<double> toArray(const Eigen::MatrixXd& m);

// A harmonic-balance solution [x; λ] (full layout): "harmonics", per channel
// "x_cos"/"x_sin" (dofs x harmonics), "lambda_cos"/"lambda_sin", one period
// sampled on the model's N instants ("t", "x", "lambda"), "max_abs_x",
// "max_abs_velocity", "max_abs_lambda", the labels, the laws' invariant
// checks and the "full" vector (a start for a later solve).
py::dict solutionDict(const HbModel& model, const Eigen::VectorXd& full);
// The solver's report: converged, termination, counts, norms, time.
py::dict resultDict(const SolverResult& result);
py::dict curveDict(const HbModel& model, const Curve& curve);
py::dict referenceDict(const HbModel& model, const TimeReference& reference);

}  // namespace eqhb::python
