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
// Also "dof_labels" (every DOF's label, the order of max_abs) and
// "peak_dof" (the label of the DOF that defines the peak) and "shown" (the
// labels of the DOFs the CSV and chart show).
nlohmann::json sweepJson(const app::SweepResult& result);
// The curve's CSV with the DOFs the scene's output choice shows
// (scenes/dof_choice.h) under their labels.
void writeSweepCsv(const std::string& path, const app::SweepResult& result);

}  // namespace eqhb::output
