// Pieces shared by the law entries (law_registry.h).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/laws/law_registry.h"

namespace eqhb {

// An entry of scene `type` with its one-line summary, the rest to fill.
inline LawEntry lawEntry(std::string type, std::string summary) {
  LawEntry e;
  e.type = std::move(type);
  e.summary = std::move(summary);
  return e;
}

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

// An exact-flow site of `kind` whose coefficient is the law's `coefficient`
// (a Coulomb limit, a cubic ε): LawEntry::smooth_flow of a law of class L.
template <class L>
std::function<std::optional<SmoothFlowSite>(const Law&)> coefficientSite(SmoothFlowSite::Kind kind,
                                                                         double (L::*coefficient)() const) {
  return [kind, coefficient](const Law& law) -> std::optional<SmoothFlowSite> {
    SmoothFlowSite site;
    site.kind = kind;
    site.coefficient = (static_cast<const L&>(law).*coefficient)();
    return site;
  };
}

}  // namespace eqhb
