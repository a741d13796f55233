// Writers of a time-domain reference (app::Simulation, `eqhb simulate`) and
// of a harmonic-balance solve compared with it (app::Comparison, `eqhb
// compare`): JSON and text. Channels are labelled as a harmonic-balance
// solution's ("x1", "law1.lambda", "law2.lambda1").
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "eqhb/app/simulate.h"

namespace eqhb::output {

// periodic, timed_out, periods, step, steps_per_period, periodicity_error,
// seconds, "dofs" [{dof, max_abs, max_abs_velocity, first_harmonic_amplitude}],
// "law_forces" [{component, label, max_abs}].
nlohmann::json referenceJson(const HbModel& model, const TimeReference& reference);
// The last period, sample i at t = iT/steps_per_period: "t", "x<i>", "v<i>",
// each law component by its label.
nlohmann::json referenceTrajectoryJson(const HbModel& model, const TimeReference& reference);
// scene, omega, the reference, and with `trajectory` its last period.
nlohmann::json simulationJson(const app::Simulation& simulation, bool trajectory);
// scene, omega, harmonics, "hb" (converged, termination, residual_norm,
// seconds), "reference", "errors" [{channel, relative_l2, ...}].
nlohmann::json comparisonJson(const app::Comparison& comparison);

void writeReferenceText(std::ostream& out, const HbModel& model, const TimeReference& reference);
void writeSimulationText(std::ostream& out, const app::Simulation& simulation);
void writeComparisonText(std::ostream& out, const app::Comparison& comparison);

}  // namespace eqhb::output
