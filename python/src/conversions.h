// Results as plain Python: numpy arrays for everything sampled or indexed by
// harmonic, dicts for the rest.
#pragma once

#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "eqhb/app/shoot.h"
#include "eqhb/app/simulate.h"
#include "eqhb/app/solution.h"
#include "eqhb/app/sweep.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/curves/curve_writers.h"
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
// The same with the channels' summary given (an orbit's exact max|x|).
py::dict solutionDict(const HbModel& model, const Eigen::VectorXd& full, const HbSolution& summary);
// A JSON value of the writers as Python objects (dicts, lists, numbers).
py::object fromJson(const nlohmann::json& value);
// A Hill analysis: the keys of the JSON writer's, multipliers and exponents
// as complex arrays.
py::dict stabilityDict(const HillResult& hill);
// app::solve's result: every key of `eqhb solve --json` (output::solutionJson),
// stability with complex multipliers, and "solution" (solutionDict of the
// answer reported).
py::dict solveDict(const app::Solution& solution);
// app::shoot's result: the keys of `eqhb shoot --json`, "from_hb" with the
// start's solver report, the monodromy, complex multipliers, "max_abs_x",
// and one period (t, x, v, lambda) with "lambda_labels".
py::dict orbitDict(const app::Orbit& orbit);
// app::simulate's and app::compare's results: referenceDict plus the JSON keys.
py::dict simulationDict(const app::Simulation& simulation);
py::dict comparisonDict(const app::Comparison& comparison);
// The solver's report: converged, termination, counts, norms, time.
py::dict resultDict(const SolverResult& result);
// The curve's converged points as arrays (one row each) and its failed
// points as a list of dicts, "failed" (output/curve_writers.h).
py::dict curveDict(const HbModel& model, const Curve& curve);
// app::sweep's result: curveDict, the run's settings of `eqhb sweep --json`
// (and its bifurcations, rho and accuracy when computed), and per converged
// point the JSON's optional fields as lists, None where a point has none:
// stable, bifurcation, spectral_radius, multipliers (complex, leading four),
// error_estimate, point_harmonics, point_samples, accuracy_met,
// accuracy_seconds, accuracy_failure.
py::dict sweepDict(const app::SweepResult& result);
py::dict referenceDict(const HbModel& model, const TimeReference& reference);

}  // namespace eqhb::python
