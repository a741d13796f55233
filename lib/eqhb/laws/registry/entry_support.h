// Pieces shared by the law entries (law_registry.h).
#pragma once

#include <vector>

#include "eqhb/error.h"
#include "eqhb/laws/law_registry.h"

namespace eqhb {

// The two keys LawTable::rho reads.
inline std::vector<LawParameter> rhoParameters() {
  return {{"rho", "", "> 0", "the scaling ρ in the problem's units (not with rho_factor)"},
          {"rho_factor", "1", "> 0", "without rho: this times the scale-free ρ set from the structure"}};
}

// `parameters` followed by the ρ keys.
inline std::vector<LawParameter> withRho(std::vector<LawParameter> parameters) {
  for (auto& p : rhoParameters()) parameters.push_back(p);
  return parameters;
}

}  // namespace eqhb
