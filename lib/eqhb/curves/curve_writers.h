// The frequency-response curve as its users read it, one model for every
// interface: the converged points form the curve (rows of the CSV, "points"
// of the JSON, the arrays of Python's dict); the points that did not
// converge are listed apart with their ω, termination and counts (a
// companion CSV, "failed" in JSON and Python), never as rows of NaN.
//
// The CSV and text writers are here; the JSON writer (curve_json.h) and
// Python's dict (python/src/conversions.cpp) read the same CurveParts.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "eqhb/continuation/continuation.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/stability/curve_stability.h"

namespace eqhb {

// A run's points split for the writers, each list in the run's order.
struct CurveParts {
  std::vector<const CurvePoint*> converged;
  std::vector<const CurvePoint*> failed;
  // Per point of the run: its index in `converged`, −1 for a failed point
  // (what a bifurcation's point index becomes in the output).
  std::vector<int> curve_index;
};
CurveParts splitCurve(const Curve& curve);

// The fields of a failed point, in the order every writer gives them.
constexpr const char* kFailedPointFields[] = {"omega",    "termination",          "iterations",
                                              "residual_evaluations", "jacobian_evaluations",
                                              "residual_norm", "seconds"};

// The DOFs a CSV shows, by index (0-based) and label ("x3", a beam's "w3").
struct CurveColumns {
  std::vector<int> dofs;
  std::vector<std::string> labels;
};
// Every DOF of `model` under its label (dofLabel, hb_solution.h), or the
// `shown` ones.
CurveColumns curveColumns(const HbModel& model);
CurveColumns curveColumns(const HbModel& model, const std::vector<int>& shown);

// The curve as CSV: one row per converged point with ω, converged, the
// termination, counts, time, max|x_i| (column max_abs_<label>), first-harmonic amplitude of x_i,
// energy, fold; when stability was computed for some point: stable (1/0,
// empty if not computed) and bifurcation; error_estimate when estimated;
// harmonics, samples, accuracy_met and accuracy_seconds when an accuracy
// target was set; fallback when a point needed one. The failed points go to
// failedCurvePath(path) (kFailedPointFields, termination quoted) when there
// are any; a stale file of that name is removed when there are none.
// Throws an I/O error naming the file that cannot be written.
void writeCurveCsv(const std::string& path, const Curve& curve, const CurveColumns& columns);
// All of `dofs` DOFs, labelled x1..xn.
void writeCurveCsv(const std::string& path, const Curve& curve, int dofs);
// "curve.csv" -> "curve.failed.csv"; any other name gets ".failed.csv" appended.
std::string failedCurvePath(const std::string& path);

// How a curve was computed, for the JSON and text writers.
struct CurveRun {
  std::string scene, solver;
  bool arclength = false;
  double from = 0.0, to = 0.0, step = 0.0;
  bool condensed = true;
  const HbModel* model = nullptr;           // the curve's discretisation (an accuracy target raises H per point)
  const CurveStability* stability = nullptr;  // when the points' stability was analysed
  std::vector<std::string> advice;          // the summary's advice when the curve is not complete
  bool error_estimate = false;              // per-point estimates were asked (not with an accuracy target)
  std::string accuracy;                     // an accuracy target's summary line, in place of the estimates' line
  int peak_dof = -1;                        // the DOF whose maximum defines the peak (−1: the last)
};
// The text summary: counts and time, the stop reason (and the advice when
// not complete), the failed points (ω and termination; neighbours that
// failed alike on one line, the first ten lines), the
// peak of run.peak_dof under its label, the folds, the largest error estimate or the
// accuracy line, stability.
void writeCurveSummary(std::ostream& out, const Curve& curve, const CurveRun& run);

}  // namespace eqhb
