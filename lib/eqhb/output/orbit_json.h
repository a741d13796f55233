// Writers of an exact periodic orbit (app::Orbit, `eqhb shoot`): JSON and text.
// DOFs are numbered from 1; the trajectory's channels are labelled as a
// harmonic-balance solution's ("x1", "v1", "law1.lambda", "law2.lambda1").
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "eqhb/app/shoot.h"

namespace eqhb::output {

// scene, omega, period, restitution, from_hb, converged (failure), period_residual,
// tolerance, iterations, flow_evaluations, start_time, state, dofs, multipliers,
// spectral_radius, stable (null without an orbit), events, seconds, seconds_per_orbit,
// and with `trajectory` (a converged orbit) one period: t, x<i>, v<i>, law labels.
nlohmann::json orbitJson(const app::Orbit& orbit, bool trajectory);
// One period of a flow's samples: "t", "x<i>", "v<i>" per DOF, each law component by its label.
nlohmann::json flowSamplesJson(const HbModel& model, const orbits::FlowSamples& samples);
void writeOrbitText(std::ostream& out, const app::Orbit& orbit);

}  // namespace eqhb::output
