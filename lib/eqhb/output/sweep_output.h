// The writers' view of an app::sweep result: how the curve was computed
// (CurveRun, for the CSV, text and JSON writers of curve_writers.h and
// curve_json.h) and the whole run as `eqhb sweep --json` prints it, with the
// accuracy target's choice and ρ when one was set.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "eqhb/app/sweep.h"
#include "eqhb/curves/curve_writers.h"

namespace eqhb::output {

// Points into `result` (its model and stability): keep it alive. The
// accuracy line names the target as the interface calls it.
CurveRun curveRun(const app::SweepResult& result, const std::string& accuracy_option = "accuracy");
// curveJson, and "rho" and "accuracy" (tolerance, reached, not_met,
// highest_harmonics, seconds, first_point) with an accuracy target.
nlohmann::json sweepJson(const app::SweepResult& result);

}  // namespace eqhb::output
