// Stability along a frequency-response curve: Hill's method at every
// converged point, and the bifurcations where the number of multipliers
// outside the unit circle changes between two neighbours.
//
// Folds are confirmed twice: a real multiplier through +1 between two
// points AND a reversal of the ω-direction of the arclength tangent within
// one point of them. On nonsmooth laws the tangent alone flickers at kinks
// (zig-zags of a few points) while no multiplier crosses; a real multiplier
// through +1 without a turn is a branch point of the (symmetric) solution,
// reported as such. On a sequential sweep there is no tangent: every real
// crossing of +1 is reported as a fold.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "eqhb/continuation/continuation.h"
#include "eqhb/stability/hill_stability.h"

namespace eqhb {

struct Bifurcation {
  int point = 0;        // index of the first point after the change
  double omega = 0.0;   // midway between the two points
  std::string kind;     // fold, branch-point, period-doubling, neimark-sacker
};

struct CurveStability {
  std::vector<HillResult> points;  // one per curve point (empty exponents if not converged)
  std::vector<Bifurcation> bifurcations;
  double seconds = 0.0;            // all Hill analyses
  double solve_seconds = 0.0;      // the curve's corrector time, for comparison
  // The time limit ran out after `analysed` of the curve's converged points
  // (in curve order); the rest have no verdict.
  bool time_limited = false;
  int analysed = 0;
};

// Analyses every converged point of `curve` (computed on `model` with ω
// changed per point), sets each point's `stable` and `bifurcation`, and
// replaces the curve's folds by the confirmed ones when the curve has
// arclength tangents.
// options.method chooses Hill's method, the monodromy
// (monodromy_stability.h) or shooting (shooting_stability.h: one
// ShootingStability for the curve, its fallbacks per point); `progress`, if
// set, is told of each point.
CurveStability analyseCurveStability(const HbModel& model, Curve& curve, const HillOptions& options = {},
                                     const std::function<void(int done, int total)>& progress = {});

// One solution's stability by options.method: throws InputError
// (stability_method) for "monodromy" or "shooting" on laws they do not
// support.
HillResult analyseStability(const HbModel& model, const Eigen::VectorXd& full, const HillOptions& options = {});

}  // namespace eqhb
