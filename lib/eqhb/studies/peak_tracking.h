// The resonance peak of a frequency-response curve, found by following the
// curve to where the first-harmonic amplitude A of one DOF is stationary.
//
// Along the solution branch z(ω) of g(z, ω) = 0 the tangent is
// dz/dω = −J_z⁻¹ ∂g/∂ω (weak Jacobian, ∂g/∂ω by a forward difference), and
// the peak condition is the bordered equation
//     φ(ω) = dA²/dω = ∇A²·(dz/dω, 1) = 0,     A² = a₁² + b₁² of the DOF.
// The extended system [g(z, ω); φ(z, ω)] = 0 is solved by nesting: the chosen
// backend solves g = 0 at fixed ω (started from the tangent predictor), and
// ω is updated by secant steps on φ, kept inside a bracket once φ has
// changed sign. A maximum needs φ decreasing through zero, and is confirmed
// by the amplitude itself at ω ± h: on nonsmooth branches the weak-Jacobian
// tangent can make φ vanish where the amplitude still climbs; there the
// maximum is found from amplitudes alone (uphill bracket, golden section).
//
// Several resonances may share [from, to], and one may vanish (friction
// damps it out) while another takes over as the largest. So every local
// maximum is followed (up to max_peaks), and the result is the largest.
// Warm start: from the peaks (ω*, z*) of a neighbouring sample, each secant
// starts at its ω* with z* as the corrector's start: a handful of solves
// per peak instead of a dense sweep; a peak that vanishes climbs to another
// one and the two merge. Cold start (no neighbour, or every warm one
// failed): a coarse sequential sweep over [from, to] brackets the local
// maxima of the amplitude, the largest max_peaks are refined the same way.
// Continuation cannot see a resonance appear that was not there before: a
// study walks each grid line from a cold start (study_plan.h), so lines
// should run the way resonances disappear (e.g. increasing normal load).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "eqhb/continuation/fallback_chain.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

struct PeakOptions {
  double from = 0.1, to = 0.8;  // the peak is searched for in [from, to]
  int dof = 0;                  // DOF (0-based) whose first-harmonic amplitude peaks
  int coarse_points = 41;       // grid points of a cold start's sweep, >= 3
  double omega_tolerance = 1e-9;  // relative: stop when |Δω| <= tol · ω
  int max_secant_steps = 40;
  int max_peaks = 4;              // local maxima followed at once, >= 1
  bool condensed = true;
  // The steps after a failed point of the cold start's sweep; null: the
  // sweeps' standard chain (cold start, full system, no other backend).
  const FallbackChain* fallbacks = nullptr;
  // Throws InputError naming the field.
  void validate(int dofs) const;
};

// Where the peaks were found: enough to warm-start the next sample.
struct PeakState {
  std::vector<double> omegas;
  std::vector<Eigen::VectorXd> z;  // the system's unknowns (condensed or full)
  bool valid() const { return !z.empty(); }
};

struct PeakResult {
  bool converged = false;
  std::string reason;        // why not, if not converged
  std::string start;         // "warm", "cold", or "cold (warm: <why>)"
  double omega = 0.0;
  std::vector<double> first_harmonic;  // per DOF, at the peak
  std::vector<double> max_abs;         // per DOF, max |x_i(t)| over a period
  int peaks = 0;                       // local maxima followed
  int solves = 0, iterations = 0;
  double seconds = 0.0;
  PeakState state;
};

// Finds the peak of `model` (its ω is ignored), warm-started from `warm` if
// it is valid and has the system's size. Never throws for numerical
// trouble (the reason is in the result); throws InputError for bad options.
PeakResult trackPeak(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                     const PeakOptions& options, const PeakState* warm = nullptr);

}  // namespace eqhb
