// One harmonic-balance solve of a scene as every interface runs it (`eqhb
// solve`, Python's eqhb.solve): the accuracy target's choice of H and ρ, the
// start (coarse harmonic balance, continuation in H or a given vector), the
// repeats, the fallback steps after a failure, then stability, the error
// estimate and the refinement by shooting on the answer.
#pragma once

#include "eqhb/app/scene_settings.h"
#include "eqhb/app/solution.h"
#include "eqhb/app/solve_options.h"

namespace eqhb::app {

// The whole solve; throws InputError naming the option or the scene's field,
// TimeLimitReached when the set-up runs out of solver_options.time_limit.
// Non-convergence is a status (Solution::converged, succeeded).
Solution solve(const SceneSettings& scene, const SolveOptions& options);

// The harmonic-balance solve alone (start, repeats, fallbacks): what shoot,
// simulate and compare start from. Ignores the options computed on the answer.
HbRun solveHarmonicBalance(const SceneSettings& scene, const SolveOptions& options);

}  // namespace eqhb::app
