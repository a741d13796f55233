// Frequency-response curves by continuation in ω, any backend as corrector.
//
//  sequential: ω on a grid from `from` to `to` (either direction), the
//    previous solution as predictor; a failed corrector halves the step
//    (intermediate points) down to min_step; a point still failed then gets
//    the fallback chain (fallback_chain.h: cold start, full system, another
//    backend), and only then counts as failed, saying why.
//  arclength (arclength.cpp): pseudo-arclength in scaled unknowns
//    ŷ = (z / s_z, ω / s_ω), s_z = ‖z‖ of the current point (floored at 10⁻³
//    of the largest so far) updated every point, s_ω = |to − from|: tangent
//    predictor from the weak Jacobian bordered by the previous tangent,
//    corrector on [g(z, ω); τᵀ(ŷ − ŷ_pred)] = 0 by the chosen backend. A
//    step whose tangent turns by more than max_turn is halved and retried;
//    a turn that does not shrink with the step is a kink, crossed along the
//    secant (and a sweep that turns back at one stops: not a fold). The step
//    follows the corrector's effort and the turn, within [min_step,
//    max_step]. The last point lies exactly on `to` (solved there with ω
//    fixed); a curve that leaves the range at `from` is not complete. Where
//    the curve cannot be followed even at min_step (a corrector failure, no
//    tangent, a kink turning back), a bridge solves with ω fixed a little
//    further on (fallbacks included) and starts afresh there, the jump said
//    on the point and in the stop reason. Folds
//    are where the ω-component of the tangent changes sign (and stays
//    changed for three points). Either direction, from < to or from > to.
//  harmonics: solve at H₀ and reuse the solution as the start at larger H.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/continuation/curve_stop.h"
#include "eqhb/continuation/fallback_chain.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// A point's check against an accuracy target (sweep --accuracy): whether
// its estimate met the tolerance, why not, and the time of the solves that
// checked and refined it.
struct PointAccuracy {
  bool met = false;
  std::string failure;
  double seconds = 0.0;
  std::string test;    // the test that decided: "exact-orbit" or "estimate" (accuracy/rung_test.h)
  double error = 0.0;  // its value: the true error, or the safety factor times the estimate
};

// One point of a continuation run. A point that did not converge keeps its
// ω, termination and counts only; the writers (output/curve_model.h) list
// such points apart from the curve.
struct CurvePoint {
  double omega = 0.0;
  bool converged = false;
  std::string termination;
  int iterations = 0, residual_evaluations = 0, jacobian_evaluations = 0;
  double seconds = 0.0;
  double residual_norm = 0.0;
  std::vector<double> max_abs;         // per DOF, over one period
  std::vector<double> first_harmonic;  // per DOF, |(a₁, b₁)|
  double energy = 0.0;                 // period mean of ½ẋᵀMẋ + ½xᵀKx
  bool fold = false;                   // a turning point lies just before this point
  std::string fallback;                // the fallback step that converged it; empty: none needed
  std::optional<double> tangent_omega; // arclength: ω-component of the unit tangent here
  std::optional<bool> stable;          // Hill stability, where it was computed
  std::string bifurcation;             // stability analysis: kind, between the previous point and this
  std::optional<double> error_estimate;  // estimated relative error of max|x|, where estimated
  // The point's own discretisation (0: the curve's), raised by an accuracy target.
  int harmonics = 0, samples = 0;
  std::optional<PointAccuracy> accuracy;  // set by an accuracy target (accuracy_sweep.h)
  Eigen::VectorXd full;                // [x; λ] coefficients
};

struct Curve {
  std::vector<CurvePoint> points;
  bool complete = false;        // reached the end of the range (exit status 0 needs it)
  std::string stop_reason;
  std::vector<double> fold_omegas;
  double seconds = 0.0;
  int failed_points = 0;        // grid points that did not converge (sequential)
};

struct ContinuationOptions {
  double from = 0.1, to = 0.8;
  double step = 0.01;           // sequential: grid step; arclength: initial Δs (scaled), clamped to the bounds
  double min_step = 1e-6;       // in ω (sequential) or scaled arclength
  double max_step = 0.1;        // arclength, scaled (ω's share of a unit step is the whole range)
  double max_turn = 0.35;       // arclength: largest turn of the tangent per step, radians (20°)
  int max_points = 20000;
  int target_iterations = 12;   // arclength step adaptation aims at this
  bool condensed = true;
  // For a sequential point that fails from the previous one (after the
  // halved steps), and for the first point of either method.
  FallbackChain fallbacks = FallbackChain::standard(nullptr);
  // The first point's start: its [x; λ] coefficients (FullSystem layout, the
  // model's H) at `from`, e.g. a solution already known there; empty: zero.
  Eigen::VectorXd start_full;
  // Ends the curve early, keeping its points (curve_stop.h): not complete,
  // the stop reason says where and why.
  CurveStop stop;
  // The step when none is given: a sequential grid of a hundredth of the
  // range (101 points in any unit: 0.007 on a nondimensional 0.1 -> 0.8,
  // 2.6 rad/s on a cantilever's 110 -> 370 rad/s), an arclength start of
  // 0.01 in the scaled unknowns.
  static double defaultStep(double from, double to, bool arclength);
  // The step bounds when none is given: min(10⁻⁶, step) and max(0.1, step)
  // (0.1: a tenth of the range in ω or a 10 % change of the response).
  static double defaultMinStep(double step) { return std::min(1e-6, step); }
  static double defaultMaxStep(double step) { return std::max(0.1, step); }
  // Throws InputError naming the field.
  void validate() const;
  // Points of the sequential grid, floor(|to − from| / step) + 1, as a
  // double (it may lie far beyond int). Call after validate().
  double gridPoints() const;
  // validate(), and for a sequential sweep a grid of at most max_points:
  // refused up front with the count, never cut short.
  void validateGrid() const;
};

using Progress = std::function<void(const CurvePoint&, int index)>;

Curve sweepSequential(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                      const ContinuationOptions& options, const Progress& progress = nullptr);
Curve sweepArclength(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                     const ContinuationOptions& options, const Progress& progress = nullptr);

// Adds a solve's counts and time to the point's and sets its termination,
// convergence and residual norm from it.
void addSolverCounts(const SolverResult& result, CurvePoint* point);

// Physical summary of a solution (max|x|, first harmonic, energy).
CurvePoint describePoint(const HbModel& model, const Eigen::VectorXd& full);
// The same written into an existing point: its `full`, `max_abs`,
// `first_harmonic` and `energy`; every other field is left as it is.
void describeInto(const HbModel& model, const Eigen::VectorXd& full, CurvePoint* point);

// Solves at `start_harmonics` then at each doubling up to the model's H,
// each seeded with the previous solution. Returns the last result; its
// solution is in the system's unknowns (condensed or full as requested).
SolverResult solveByHarmonicContinuation(const HbModel& model, Solver& solver, const SolverOptions& options,
                                         int start_harmonics, bool condensed, Eigen::VectorXd* full = nullptr);

}  // namespace eqhb
