// The computations that read one DOF per law component (the exact orbits'
// flows) refuse elements between nodes through this check, which names the
// law and the computation.
#pragma once

#include <string>
#include <vector>

#include "eqhb/laws/law.h"

namespace eqhb {

// Throws InputError naming law[l] when a law is not grounded (an element
// between two nodes or along a slanted direction); `computation` says what
// refuses it, e.g. "exact orbits (shooting)".
void requireGroundedLaws(const std::vector<AttachedLaw>& laws, const std::string& computation);

}  // namespace eqhb
