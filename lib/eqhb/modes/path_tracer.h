// The nonlinear mode's path followed in pseudo-arclength from the linear
// mode at the smallest amplitude (backbone.h has the account): the tracer
// behind followBackbone, kept apart from the backbone's public types.
#pragma once

#include "eqhb/modes/backbone.h"
#include "eqhb/modes/mode_system.h"
#include "eqhb/preload/static_contact.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// The mode at amplitude a from a solution z of `system` (the solver's counts
// and `converged` left for the caller).
BackbonePoint describeModePoint(const ModeSystem& system, const Eigen::VectorXd& z, double a);

// The linear mode at amplitude a as a start of `system`: x̂ = a φ cos ωt,
// the laws' forces those that supply its reaction (lawForcesFor), ω and
// ξ = 2ζω of `mode`, plus the static state's constant terms when `at_rest`.
// On a system other than the full one, as it takes such a guess
// (ModeSystem::fromFullPoint).
Eigen::VectorXd linearStart(const ModeSystem& system, const LinearMode& mode, double a,
                            const StaticContactState* at_rest);

// Fills `backbone`'s points, folds and stop (its `start` set by the caller)
// on `system`, built on the start's shape. Throws InputError when the solver
// rejects its options.
void tracePath(ModeSystem& system, Solver& solver, const SolverOptions& solver_options, const BackboneOptions& o,
               const BackboneProgress& progress, const StaticContactState* at_rest, Backbone* backbone);

}  // namespace eqhb
