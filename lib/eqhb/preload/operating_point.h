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
// after one step of `solver` on the full system (a Newton step when the
// solver takes it whole), exact while every contact keeps its static state
// over the period (a slider stuck, a contact closed). The start of the
// dynamic solve under a preload: from the operating point itself the
// condensed system's first iterate holds the contact forces at their static
// values and lets the structure respond freely, which can swing preloaded
// contacts open (two beams pressed over a lap joint). The operating point
// when that step does not lower the full residual or fails to set up.
Eigen::VectorXd linearisedStart(const HbModel& model, const StaticContactState& state, Solver& solver,
                                const SolverOptions& options);

// `model` with each law anchored at its static state where it has one.
HbModel anchoredAtRest(HbModel model, const StaticContactState& state);

}  // namespace eqhb
