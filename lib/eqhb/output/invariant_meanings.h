// What each law invariant (Law::violations) measures and when it is
// expected to be non-zero, for the text outputs: the exact law makes every
// one 0, but a converged solve of a truncated Fourier series only
// approaches the non-smooth law, so a value such as sliding_force_error
// 0.44 is the Gibbs ringing of the series at a stick–slip switch, not a
// failed solve. The JSON keeps the bare names and values.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/invariants.h"

namespace eqhb::output {

// One line per invariant name, or "" for a name without one.
std::string invariantMeaning(const std::string& name);

// "  what the invariants measure ..." and one line per kind reported in
// `reports` (each once, in the order first met); nothing when there are none.
void writeInvariantMeanings(std::ostream& out, const std::vector<LawInvariants>& reports);

}  // namespace eqhb::output
