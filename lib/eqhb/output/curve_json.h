// The curve as one JSON object (`eqhb sweep --json`): the run's settings,
// stop reason and folds, "points" (the converged points: counts, amplitudes,
// each point's Fourier coefficients of every DOF and law force, stability),
// "failed" (the points that did not converge, kFailedPointFields) and the
// bifurcations, whose "point" indexes "points".
#pragma once

#include <nlohmann/json.hpp>

#include "eqhb/curves/curve_writers.h"

namespace eqhb {

nlohmann::json curveJson(const Curve& curve, const CurveRun& run);

}  // namespace eqhb
