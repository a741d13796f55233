// Why a sweep may find no point: the worst-resolved law force among some of
// its converged points (force_resolution.h), as a clause for its stop reason
// or a failed point's termination.
#pragma once

#include <string>
#include <vector>

#include "eqhb/continuation/continuation.h"

namespace eqhb {

// "; law 1's force ... is not resolved at H = 40 near omega = ...", from the
// converged point among `points` whose law force rises most toward the
// truncation (points on the curve's own harmonics only); empty if none rises.
std::string unresolvedForceClause(const HbModel& model, const std::vector<const CurvePoint*>& points);

}  // namespace eqhb
