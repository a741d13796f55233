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
// changed sign. A maximum needs φ decreasing through zero.
//
// Warm start: from the peak (ω*, z*) of a neighbouring sample, the secant
// starts at ω* with z* as the corrector's start: a handful of solves per
// sample instead of a dense sweep. Cold start (no neighbour, or the warm
// one failed): a coarse sequential sweep over [from, to] brackets the
// largest amplitude, then the same secant refines it.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

struct PeakOptions {
  double from = 0.1, to = 0.8;  // the peak is searched for in [from, to]
  int dof = 1;                  // DOF (from 1) whose first-harmonic amplitude peaks
  int coarse_points = 41;       // grid points of a cold start's sweep, >= 3
  double omega_tolerance = 1e-9;  // relative: stop when |Δω| <= tol · ω
  int max_secant_steps = 40;
  bool condensed = true;
  // Throws InputError naming the field.
  void validate(int dofs) const;
};

// Where a peak was found: enough to warm-start the next sample.
struct PeakState {
  double omega = 0.0;
  Eigen::VectorXd z;  // the system's unknowns (condensed or full)
  bool valid() const { return z.size() > 0; }
};

struct PeakResult {
  bool converged = false;
  std::string reason;        // why not, if not converged
  std::string start;         // "warm", "cold", or "cold (warm: <why>)"
  double omega = 0.0;
  std::vector<double> first_harmonic;  // per DOF, at the peak
  std::vector<double> max_abs;         // per DOF, max |x_i(t)| over a period
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
