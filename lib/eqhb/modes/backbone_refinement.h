// More modes between a backbone's recorded amplitudes, where a use of the
// backbone needs it denser than its grid (the synthesis of a forced
// response near its peak, mode_synthesis.h): each solved with the amplitude
// fixed from the interpolation, in log a, of the two points around it.
#pragma once

#include "eqhb/modes/backbone.h"
#include "eqhb/preload/static_contact.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// Inserts `per_interval` modes, evenly in log a, between each two converged
// points consecutive in the path's order whose amplitudes differ and both
// lie in [from, to]; a solve that fails adds nothing (the backbone's grid
// points and failed count are unchanged). Returns how many were added.
// `model`, `at_rest`: as given to followBackbone.
int refineBackbone(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                   const StaticContactState* at_rest, double from, double to, int per_interval, Backbone* backbone);

}  // namespace eqhb
