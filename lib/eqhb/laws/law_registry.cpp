#include "eqhb/laws/law_registry.h"

#include <algorithm>
#include <stdexcept>

namespace eqhb {

// One function per law, each in its own file under laws/registry/.
LawEntry coulomb1DEntry();
LawEntry coulomb2DEntry();
LawEntry signoriniEntry();
LawEntry stribeckEntry();
LawEntry cubicEntry();
LawEntry contactFrictionEntry();
LawEntry jenkinsEntry();
LawEntry iwanEntry();
LawEntry penaltyContactEntry();
LawEntry polynomialEntry();
LawEntry quadraticDampingEntry();
LawEntry elasticFrictionEntry();

const std::vector<LawEntry>& lawRegistry() {
  static const std::vector<LawEntry> entries = {coulomb1DEntry(), coulomb2DEntry(),       signoriniEntry(),
                                                stribeckEntry(),  cubicEntry(),           contactFrictionEntry(),
                                                jenkinsEntry(),   iwanEntry(),            penaltyContactEntry(),
                                                polynomialEntry(), quadraticDampingEntry(), elasticFrictionEntry()};
  return entries;
}

bool LawEntry::takesRho() const {
  return std::any_of(parameters.begin(), parameters.end(), [](const LawParameter& p) { return p.key == "rho"; });
}

bool LawEntry::hasForm(const std::string& form) const {
  return std::find(forms.begin(), forms.end(), form) != forms.end();
}

std::string defaultFormulation(const LawEntry& entry, const LawTable& table) {
  if (!entry.parse) return "aft";
  // Asked only of laws that have these keys: the unknown-key message lists
  // every key a parser asked about.
  if (!entry.aft_by_default || !entry.aft_by_default(table)) return "equality";
  const bool equality_keys = table.has("form") || table.has("rho") || table.has("rho_factor");
  return equality_keys ? "equality" : "aft";
}

bool inAftForm(const Law& law) {
  const LawEntry& entry = lawEntry(law);
  return !entry.parse || (entry.in_aft_form && entry.in_aft_form(law));
}

std::shared_ptr<Law> parseLaw(const LawEntry& entry, LawTable& table) {
  const std::string formulation = table.text("formulation", defaultFormulation(entry, table));
  if (formulation != "equality" && formulation != "aft")
    table.fail(table.path("formulation"), "\"" + formulation + "\"", "must be \"equality\" or \"aft\"");
  const bool aft = formulation == "aft";
  if (aft ? !entry.parse_aft : !entry.parse) {
    std::string with;
    for (const LawEntry& e : lawRegistry())
      if (aft ? bool(e.parse_aft) : bool(e.parse)) with += (with.empty() ? "" : ", ") + e.type;
    table.fail(table.path("formulation"), "\"" + formulation + "\"",
               "a " + entry.type + " law has no " + (aft ? "alternating frequency-time" : "equality") +
                   " form (laws with one: " + with + ")");
  }
  return aft ? entry.parse_aft(table) : entry.parse(table);
}

const LawEntry* findLaw(const std::string& type) {
  for (const LawEntry& entry : lawRegistry())
    if (entry.type == type) return &entry;
  return nullptr;
}

const LawEntry& lawEntry(const Law& law) {
  const LawEntry* entry = findLaw(law.type());
  if (!entry) throw std::logic_error("law type " + law.type() + " is not registered (law_registry.cpp)");
  return *entry;
}

std::string knownLawTypes() {
  std::string list;
  for (const LawEntry& entry : lawRegistry()) list += (list.empty() ? "" : ", ") + entry.type;
  return list;
}

// A law built in code without an entry has no capability and no preference.
std::optional<SmoothFlowSite> smoothFlowSite(const Law& law) {
  const LawEntry* entry = findLaw(law.type());
  return entry && entry->smooth_flow ? entry->smooth_flow(law) : std::nullopt;
}

std::optional<PiecewiseLinearSite> piecewiseLinearSite(const Law& law) {
  const LawEntry* entry = findLaw(law.type());
  return entry && entry->piecewise_linear_flow ? entry->piecewise_linear_flow(law) : std::nullopt;
}

bool suitsCondensedSystem(const std::vector<AttachedLaw>& laws) {
  return std::none_of(laws.begin(), laws.end(), [](const AttachedLaw& a) {
    const LawEntry* entry = findLaw(a.law->type());
    return entry && entry->system == LawSystem::kFull;
  });
}

}  // namespace eqhb
