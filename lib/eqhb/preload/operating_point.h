// The static state under a preload as the operating point of the dynamic
// solve: harmonic 0 starts at the static displacements and forces, and a
// law whose stuck state a periodic orbit leaves free (Law::anchoredAt) is
// anchored where the static load left it.
#pragma once

#include <Eigen/Dense>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/preload/static_contact.h"

namespace eqhb {

// The full coefficient vector [x; λ] on `model`'s basis whose constant terms
// are the static state's and every other coefficient 0. Throws InputError
// naming "preload" when the basis has no harmonic 0.
Eigen::VectorXd operatingPoint(const HbModel& model, const StaticContactState& state);

// `model` with each law anchored at its static state where it has one.
HbModel anchoredAtRest(HbModel model, const StaticContactState& state);

}  // namespace eqhb
