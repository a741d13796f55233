// The text report of a harmonic-balance solve (`eqhb solve` without --json):
// settings, the solver's one-line summary, start, fallbacks, linear algebra,
// max| | of every channel by its label, and the optional parts.
#pragma once

#include <ostream>

#include "eqhb/app/solution.h"

namespace eqhb::output {

void writeSolutionText(std::ostream& out, const app::Solution& solution);

}  // namespace eqhb::output
