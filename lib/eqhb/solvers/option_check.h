// The backend-specific options (`--option NAME=VALUE`) and the option set a
// user gave, checked once before a sweep or a study starts. A backend refuses
// options it cannot take when a solve begins (kInvalidOptions); in a sweep
// every point would then fail the same way and the sweep end as if the
// problem had no solution. Asked up front, the refusal is bad input.
#pragma once

#include "eqhb/solvers/solver.h"

namespace eqhb {

// Throws InputError("options: " + the backend's reason) when `solver`
// refuses `options`. The backend is asked on a system of two linear
// equations, solved at its start: every backend reads its settings before
// the first evaluation, and two unknowns is the least any of them takes
// (NLopt's NEWUOA refuses one). Refusals that depend on the problem's size
// (a dense backend and a very large system) come at the first solve.
void checkSolverOptions(Solver& solver, const SolverOptions& options);

}  // namespace eqhb
