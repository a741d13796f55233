// A nonlinear mode's backbone (app::ModesRun) as JSON (`eqhb modes --json`,
// Python's dict), CSV (one row a point) and text: per point the modal
// amplitude, ω, ζ, ξ, the energy dissipated per cycle, max|x| per DOF (in
// CSV under the DOF's name, "max_abs_w3"; in JSON "dof_labels" names them)
// and, in JSON, the Fourier coefficients of every DOF and law force.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "eqhb/app/modes.h"

namespace eqhb::output {

nlohmann::json backboneJson(const app::ModesRun& run);
// Header then one row per point; a point that did not converge keeps its
// amplitude and termination, NaN elsewhere.
void writeBackboneCsv(std::ostream& out, const app::ModesRun& run);
void writeBackboneText(std::ostream& out, const app::ModesRun& run);

}  // namespace eqhb::output
