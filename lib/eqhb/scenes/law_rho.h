// The scaling ρ of each law of a scene, as the file (with its overrides)
// sets it: what a choice of ρ scales. Defined with the scene reader, which
// owns the document and its overrides.
#pragma once

#include <string>
#include <vector>

namespace eqhb {

// Per law of the scene, in order: its ρ (1 when not given), NaN for a law
// without ρ. Throws InputError as loadScene does.
std::vector<double> lawRhos(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace eqhb
