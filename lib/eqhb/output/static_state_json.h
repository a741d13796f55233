// The static state under a preload (preload/static_contact.h) as JSON: the
// static solve's verdict, displacements, and each law's state at rest (open,
// closed, stuck or slipping, with its gap, normal force, tangential force and
// limit where the law has them).
#pragma once

#include <nlohmann/json.hpp>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/preload/static_contact.h"

namespace eqhb::output {

nlohmann::json staticStateJson(const HbModel& model, const StaticContactState& state);

}  // namespace eqhb::output
