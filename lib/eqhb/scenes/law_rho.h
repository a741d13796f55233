// The scaling ρ of each law of a scene, as the file (with its overrides)
// sets it: what a choice of ρ scales. Defined with the scene reader, which
// owns the document and its overrides.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eqhb/laws/law.h"

namespace eqhb {

// Per law of the scene, in order: its ρ as given (rho), or scale-free with
// its rho_factor (1 when not given); nullopt for a law without ρ. Throws
// InputError as loadScene does.
std::vector<std::optional<RhoSetting>> lawRhos(const std::string& path, const std::vector<std::string>& overrides = {});

// The same for a scene document held as text (parseScene's `text` and `source_name`).
std::vector<std::optional<RhoSetting>> lawRhosOfText(const std::string& text, const std::string& source,
                                                     const std::vector<std::string>& overrides = {});

// The override that sets law `l`'s ρ to `setting` times `factor` (its rho,
// or its rho_factor when scale-free).
std::string scaledRhoOverride(int l, const RhoSetting& setting, double factor);

}  // namespace eqhb
