// The default path of a solve that failed: further attempts, in a fixed
// order, before a point is given up.
//
//   1. cold   the coarse start, then zero (CoarseStart), when the failed
//             solve started elsewhere (a sweep's previous point): past a fold
//             the branch it came from no longer exists.
//   2. full   the same ω on the full system (the condensed one failed): its
//             unknowns keep x, which conditions some contacts better.
//   3. condensed  the same ω on the condensed system (the full one failed),
//             its answer polished on the full system: eliminating x removes
//             the stiff linear equations a stalled full solve fights.
//   4. SOLVER another backend on the system, from the cold start (the caller
//             names it: the core knows no backend by name), on its own
//             defaults: the backend-specific options are the failed solve's.
//   5. full:SOLVER  another backend on the full system, from its cold start
//             (the caller names it): Ceres' Levenberg-Marquardt there solves
//             the damper above its peak at H >= 25 (omega = 1.1, H = 40: 13
//             iterations from rest), where the own dogleg and Ipopt's least
//             squares stall on both systems and LM stalls on the condensed one.
//   6. forcing  a homotopy in the dynamic loads (harmonic >= 1): a quarter of
//             them solved cold, then raised to the whole, each solve from the
//             last (the step doubled after a success, halved after a
//             failure): where ‖g‖ has a local minimum that every backend
//             stalls in from rest (contact at ω = 0.5, H = 40), the load
//             raised in steps keeps each solve near its answer.
//   7. omega  continuation in ω from ω/2 up, else from 2ω down, each side
//             started cold there (omega_fallback.h, which says why these):
//             where the answer lies on a resonant branch bent by the
//             nonlinearity that no cold solve at ω reaches (penalty-contact
//             at ω = 0.7: every step above stalls, |g| 0.45; from 0.35 up
//             in 11 steps it is the sweep's point). Last: the steps before
//             it converge what they did at the same cost.
//
// Measured on the shipped scenes' sequential sweeps with the own dogleg: the
// points that failed from the previous point (Duffing and the cubic chain
// just past their folds, the damper above ω = 1.11, contact near its
// grazing frequencies) converge cold; contact-friction-2d at ω = 0.15 only
// on the full system; cubic at ω = 0.8 only with Ipopt. From rest on the
// full system: friction-2d (tanh form) and the damper (min normal form)
// only on the condensed system.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/preload/static_contact.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

struct FallbackChain {
  // Steps in order: "cold", "full", "condensed", "forcing", "omega", a backend supplied in
  // `solvers` by its Solver::name(), or "full:" and that name (the backend on
  // the full system; on the full system itself, the same as its name, skipped
  // where the chain names that too). Empty: no fallback.
  std::vector<std::string> steps;
  std::vector<Solver*> solvers;  // the backends named in `steps`, owned by the caller
  // A preloaded problem's static state (null: none). Every step's cold start
  // then begins at the response linearised about it (operating_point.h)
  // instead of at zero: from zero, a bolted joint near its resonance can
  // converge to a harmonic balance whose contacts pull, an answer of the
  // equations that is not the orbit about the static state.
  std::shared_ptr<const StaticContactState> at_rest;

  // The default order: cold, full, condensed, `backup` (may be null: no
  // backend step), full:`full_backup` (may be null), forcing, omega.
  static FallbackChain standard(Solver* backup, Solver* full_backup = nullptr);
  // The same without the forcing, omega and full:NAME steps: for a sweep's point
  // after a converged one, which its continuation in ω (from the previous
  // point, then from the next) serves better. There the homotopy's up to 40
  // solves per failed point made nlvib-03-unilateral-spring's H = 40 sweep 5x
  // slower (98 s for 20 s), and full:ceres-lm's 1000 iterations per failed
  // point its default sweep 3x slower (75 s for 244 s), each rescuing no
  // point that the next point did not.
  FallbackChain forWarmPoints() const;
  // The steps that run the failed solve's own backend again (cold, full,
  // condensed): for the rungs of an accuracy ladder above its first, warm
  // from the rung below at H >= 10, where another backend's solve or the
  // forcing homotopy costs minutes (full:ceres-lm on contact at H = 160:
  // more than 10 minutes and 2 GB before it was stopped).
  FallbackChain withOwnBackendOnly() const;
  // The same without the step "omega": for an arclength bridge, a jump a
  // little further along a curve being traced, where continuation in ω from
  // ω/2 or 2ω would retrace the curve (and up to twice kMostSolves solves per
  // bridge fraction to find a point the bridge then refuses as retraced).
  FallbackChain withoutOmegaContinuation() const;
  // Parses "cold,full,condensed,forcing,omega,NAME,full:NAME" (or "none"); `solver_for` returns the backend for a
  // NAME that is neither cold nor full, or null for an unknown one. Throws
  // InputError naming `field` for an unknown, empty or repeated step.
  static FallbackChain parse(const std::string& text, const std::string& field,
                             const std::function<Solver*(const std::string&)>& solver_for);
};

// One attempt of the chain: its step and how it ended.
struct FallbackAttempt {
  std::string step;
  SolverResult result;
  std::string note;  // what the step did, where it says more than its result ("omega": where it started)
};

struct FallbackReport {
  std::vector<FallbackAttempt> attempts;  // each step tried, in order
  std::string taken;                      // the step that converged; empty if none did
  double seconds = 0.0;                   // all attempts
};

// After `failed` (a solve of `system` at its ω that did not converge, from
// `start`): the chain's steps until one converges. Returns that result with
// its solution in `system`'s unknowns (a full-system answer mapped back), or
// `failed` when no step converged. options.time_limit bounds all the steps
// together. A step that cannot be set up (a singular A_k, memory) is recorded
// as failed with the reason.
SolverResult solveWithFallbacks(HbSystem& system, Solver& solver, const SolverOptions& options,
                                const SolverResult& failed, bool started_cold, const FallbackChain& chain,
                                FallbackReport* report);

// Where the condensed system cannot be set at ω at all (A_k singular: an
// undamped structure exactly at a harmonic's resonance), the chain's "full"
// step alone applies: the full system at ω, from its cold start. Returns
// that result, its [x; λ] in `full`, or a result that is not converged when
// the chain has no "full" step.
SolverResult solveWhereCondensationIsSingular(const HbModel& model, double omega, Solver& solver,
                                              const SolverOptions& options, const FallbackChain& chain,
                                              Eigen::VectorXd* full, FallbackReport* report);

// "cold (dogleg: not_progressing after 25 iterations), full (converged)" — one line for messages.
std::string describeFallbacks(const FallbackReport& report);

}  // namespace eqhb
