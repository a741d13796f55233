// A frequency-response curve whose every point meets an accuracy target:
// the relative error of max|x| <= tolerance by the ladder's test
// (rung_test.h: the exact orbit shot from each point where the scene allows,
// else the estimate times its safety factor).
//
// Why this design: the estimate of a solution at H needs its solve at 2H,
// so a point that ends on rung H costs the solves of its ladder up to 2H,
// dominated by the top ones; the exact test costs one shot per rung instead
// of the solve at 2H (a point met at its first rung: no solve at all). The curve's H is chosen once, at the first
// frequency (chooseDiscretisation, which also picks ρ among candidates), and the whole curve is swept at that H with
// the usual warm starts (sequential or arclength, so step halving and turning
// points work as without a target). Then every converged point is checked by
// its solve at 2H, started from the point padded with zero harmonics, and
// where the estimate is above the tolerance (typically near a resonance or a
// stick–slip transition that the first frequency did not see) H is raised on
// that point alone, by doublings, each rung started from the one below.
// H never falls below the first point's choice: the estimate of H/2 would
// need its own solve, and off-resonance points are cheap anyway.
#pragma once

#include <string>
#include <vector>

#include "eqhb/accuracy/accuracy_target.h"
#include "eqhb/continuation/continuation.h"

namespace eqhb {

struct AccurateCurve {
  // Per point: harmonics and samples of its discretisation, error_estimate,
  // accuracy (met, failure, seconds), and max|x|, first harmonic, energy and
  // coefficients (`full`) of the chosen solution.
  Curve curve;
  AccuracyChoice first;      // the ladder at the first frequency
  HbModel model;             // the curve's discretisation: H and N chosen at the first frequency
  double tolerance = 0.0;
  std::vector<double> not_met;  // ω of the converged points whose estimate stayed above the tolerance
  int highest_harmonics = 0;    // the largest H chosen on the curve
  double seconds = 0.0;         // the first ladder, the sweep and every point's ladder
};

// Throws InputError naming accuracy, max_harmonics or harmonics (the
// first H, start_harmonics) as chooseHarmonics does, before any solve.
// `candidates`: the scene's model and its variants (ρ scaled) that the first
// frequency's ladder chooses from (chooseDiscretisation); the curve keeps the
// chosen one.
AccurateCurve sweepToAccuracy(const std::vector<HbModel>& candidates, double tolerance, int start_harmonics, int max_harmonics,
                              Solver& solver, const SolverOptions& solver_options,
                              const ContinuationOptions& options, bool arclength,
                              const Progress& sweep_progress = nullptr, const Progress& check_progress = nullptr,
                              const AccuracyTestOptions& test = {});

// Each converged point's error estimate (estimateError at the point's ω on
// `model`); a point whose solve at 2H fails gets none.
void estimateCurveErrors(const HbModel& model, Solver& solver, const SolverOptions& options, bool condensed,
                         Curve* curve);

// The model of one point of such a curve: `curve_model` at the point's ω
// and on its harmonics (doublings of the curve's H, N following H).
HbModel pointModel(const HbModel& curve_model, const CurvePoint& point);

}  // namespace eqhb
