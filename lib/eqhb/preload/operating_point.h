// The static state under a preload as the operating point of the dynamic
// solve: harmonic 0 starts at the static displacements and forces, and a
// law whose stuck state a periodic orbit leaves free (Law::anchoredAt) is
// anchored where the static load left it.
#pragma once

#include <Eigen/Dense>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/preload/static_contact.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// The full coefficient vector [x; λ] on `model`'s basis whose constant terms
// are the static state's and every other coefficient 0. Throws InputError
// naming "preload" when the basis has no harmonic 0.
Eigen::VectorXd operatingPoint(const HbModel& model, const StaticContactState& state);

// The response linearised about the static state: the operating point
// plus the Newton step of the full system there, J⁻¹ of the weak Jacobian
// (every slider stuck, every contact as the static state left it) applied
// to the dynamic loads — the linear stuck system's response. Exact while
// every contact keeps its static state over the period. The start of the
// dynamic solve under a preload: from the operating point itself the
// condensed system's first iterate holds the contact forces at their static
// values and lets the structure respond freely, which can swing preloaded
// contacts open (two beams pressed over a lap joint).
// Taken whatever the full residual there: at the operating point that
// residual is the dynamic loads alone, the laws exactly met, while near a
// resonance the linear response overruns the sliders' limits, so the full
// residual would rank the operating point first exactly where the start
// matters (the lap joint at its 1534 rad/s peak: 0.47 against 0.026; the
// condensed solve from the operating point stalls, |g| 12.3 -> 3.4 in 39
// iterations, from the linear response it converges in 22). The operating
// point only when the Jacobian there is singular (an undamped structure at
// a resonance) or the step is not finite.
Eigen::VectorXd linearisedStart(const HbModel& model, const StaticContactState& state,
                                const SolverOptions& options);

// `model` with each law anchored at its static state where it has one.
HbModel anchoredAtRest(HbModel model, const StaticContactState& state);

}  // namespace eqhb
