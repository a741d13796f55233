// A mode's synthesised forced response and its forced sweep
// (app::SynthesisComparison) as JSON (the "synthesis" object of `eqhb modes
// --synthesis --json` and Python's dict) and text.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "eqhb/app/synthesis.h"

namespace eqhb::output {

nlohmann::json synthesisJson(const app::SynthesisComparison& c);
void writeSynthesisText(std::ostream& out, const app::SynthesisComparison& c);

}  // namespace eqhb::output
