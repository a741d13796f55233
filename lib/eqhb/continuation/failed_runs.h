// The last resort of a sequential sweep: grid points that failed from the
// point before them, from the fallback chain and from the point after them.
//
// Such a run of points lies where neither neighbour's branch can be reached
// by a fixed-ω solve: on a stretch of the branch the grid steps over (an
// S-shaped turn between two folds, whose middle lies backwards in ω), or
// where the branch followed folds back and the harmonic balance has no
// solution on it at this H and N. The two are told apart by following the
// branch from each converged neighbour by arclength across the run: where it
// crosses a failed point's ω, the point is solved there from the arc (its
// fallback "by arclength"); where it folds back first, the point keeps its
// failure and says so ("the branch from omega = 0.126 folds back at
// 0.1266"). Measured on contact-friction-2d at H = 40 (N = 2048): the points
// 0.127 and 0.128 lie between a fold of the branch from below at 0.12660 and
// one of the branch from above; the time reference there is periodic and
// smooth, and the harmonic balance at this H does not settle with N.
#pragma once

#include "eqhb/continuation/continuation.h"

namespace eqhb {

// Follows the branch from each converged neighbour of every run of failed
// points of `curve` (a sequential sweep of `model` by `options`) across the
// run: solves the points it crosses and adds to the termination of the
// others where the branches end. Updates curve->failed_points.
void followBranchesAcrossFailedRuns(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                                    const ContinuationOptions& options, Curve* curve);

}  // namespace eqhb
