// A friction-damped structure's mode followed down in amplitude from the
// structure without its laws (backbone.h, ModeBranch::kSliding): at large
// amplitude every friction contact slides and its force, bounded, matters
// less and less, so the mode tends to the free structure's; the branch is
// started there, at `to`, and continued down to `from`.
#pragma once

#include "eqhb/modes/backbone.h"
#include "eqhb/modes/mode_system.h"
#include "eqhb/preload/static_contact.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// Fills `backbone`'s points (increasing in amplitude) and stop, from the
// free mode `backbone->start` at `o.to` down the grid: each amplitude solved
// with the amplitude fixed from the secant through the two last solutions
// (in log a), a failed solve retried through intermediate amplitudes,
// halving the step up to max_halvings times; a grid amplitude still failing
// is a failed point and the descent goes on from the last solution. Throws
// InputError when the solver rejects its options.
void traceSlidingBranch(ModeSystem& system, Solver& solver, const SolverOptions& solver_options,
                        const BackboneOptions& o, const BackboneProgress& progress,
                        const StaticContactState* at_rest, Backbone* backbone);

}  // namespace eqhb
