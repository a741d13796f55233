// The fallback chain's step "omega": continuation in ω to the asked ω from a
// frequency where the cold start converges, for a point that no cold solve
// at its own ω reaches.
//
// Why: on a branch bent by the nonlinearity the answer at ω may lie on a
// resonant branch that only continuation from one side reaches. penalty-
// contact at ω = 0.7 (hardening: its peak at 0.79 lies above the linear mode
// at 0.62) stalls from every cold start, other backend and the forcing
// homotopy (|g| 0.45), while its sweep from 0.3 passes 0.7 converged.
//
// Where from (kBelow, then kAbove): ω/2 first. A hardening branch is single
// valued below the linear resonance it bends away from, and ω/2 lies below
// that resonance for every ω up to twice it, so the cold start there is near
// the linear response and the walk up follows the branch a sweep from low ω
// follows (it is the sequential sweep's answer wherever that sweep passes
// ω). Then 2ω, walking down: a softening branch (friction, a negative cubic)
// bends the other way and its resonant part below the linear resonance is
// reached from above. ω/2 and 2ω rather than nearer: nearer starts sit on the
// bent part themselves, where the cold start is what failed; farther ones
// cross more resonances (a walk that meets a fold fails and the other side
// is tried).
//
// How: the sequential sweep's stepping (continuation.h) — the secant of the
// last two points as predictor where it has the smaller scaled residual
// (secant_guess.h), a tenth of the way as the first step, doubled (up to
// that) after a success, halved after a failure down to 1/64 of it — on a
// system of its own, the answer then polished on the caller's system at ω.
// Bounded: at most kMostSolves solves per side, and options.time_limit for
// the whole step.
#pragma once

#include <string>

#include <Eigen/Dense>

#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/preload/static_contact.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

struct OmegaWalk {
  static constexpr double kBelow = 0.5, kAbove = 2.0;  // start frequencies, times ω, in this order
  static constexpr int kStepsAcross = 10;              // the first (and largest) step: a tenth of the way
  static constexpr int kHalvings = 6;                  // then down to 1/64 of it
  static constexpr int kMostSolves = 60;               // per side, the cold start's included
};

// Solves `system` at its ω by continuation in ω from OmegaWalk's starts,
// each started cold (the coarse start; about `at_rest` when not null, as the
// chain's other steps). Returns the polished result at ω in `system`'s
// unknowns, iterations and evaluations of every solve together, or the last
// failure. `note` (may be null) gets where the converged walk started and
// how many steps it took, or why each side failed.
SolverResult solveByOmegaContinuation(Solver& solver, HbSystem& system, const SolverOptions& options,
                                      const StaticContactState* at_rest, std::string* note);

}  // namespace eqhb
