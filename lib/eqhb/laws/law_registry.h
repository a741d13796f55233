// The law registry: every law type is declared once, in its own entry file
// (laws/registry/*_entry.cpp), with its scene name, forms, parameters, parser,
// the system that suits it, conformance examples and optional capabilities.
// The scene reader, the command line, the tests, the orbit integrators and the
// bench find laws here by name and ask for capabilities instead of casting.
//
// Adding a law: its class (laws/*.h, *.cpp), its entry file returning a
// LawEntry, and one line in lawRegistry() (law_registry.cpp); see
// docs/extending.md.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/laws/law.h"
#include "eqhb/laws/law_capabilities.h"
#include "eqhb/laws/law_table.h"

namespace eqhb {

// One key of the law's scene table.
struct LawParameter {
  std::string key;
  std::string fallback;  // the default as written in a scene; empty: required
  std::string range;     // the valid values, as the parser checks them
  std::string doc;       // one line
};

// The system a law is best solved on by default where a caller chooses
// (bench tables, studies): the condensed one (unknowns: the law forces) or
// the full one (displacements and forces).
enum class LawSystem { kCondensed, kFull };

// A parameter set the conformance tests (tests/law_registry_test.cpp) build
// the law from, through its parser: `keys` are the TOML lines of its table
// besides type and dofs; the law acts on `dofs` DOFs.
struct LawExample {
  std::string label;
  int dofs = 1;
  std::string keys;
};

struct LawEntry {
  // The scene's `type` and Law::type() of the one class the entry builds
  // (capabilities take a law of that type to be of that class).
  std::string type;
  std::string summary;  // one line
  // The forms `form` accepts (empty: none); the overrides of --form set a
  // form on the laws that list it.
  std::vector<std::string> forms;
  std::vector<LawParameter> parameters;  // every key the parser reads
  // Scene table → law, with InputErrors naming the field; the DOF count is
  // checked against Law::dimension() by the caller. Empty for a law that has
  // only the alternating frequency–time form (its default formulation).
  std::function<std::shared_ptr<Law>(LawTable&)> parse;
  // The alternating frequency–time form (formulation = "aft": the force
  // computed in time from the displacement and projected, Ψ = λ − F[x]);
  // empty when the law has none.
  std::function<std::shared_ptr<Law>(LawTable&)> parse_aft;
  // The tables whose default formulation is "aft" (empty: none beyond a law
  // without an equality form): the force then comes exact for the
  // displacement by the return map, 10-400x closer per harmonic than the
  // equality form on elastic dry friction and faster. A table naming one
  // of the equality form's own keys (form, rho, rho_factor) asks for that
  // form and keeps it.
  std::function<bool(const LawTable&)> aft_by_default;
  // True for an instance built by parse_aft (empty: a law without an
  // equality form is always in its AFT form).
  std::function<bool(const Law&)> in_aft_form;
  LawSystem system = LawSystem::kCondensed;
  std::vector<LawExample> examples;
  // Optional capabilities (law_capabilities.h); empty when the law has none,
  // nullopt for an instance that has not (a Jenkins law on two DOFs).
  std::function<std::optional<SmoothFlowSite>(const Law&)> smooth_flow;
  std::function<std::optional<PiecewiseLinearSite>(const Law&)> piecewise_linear_flow;

  // Has the scaling ρ (a `rho` parameter).
  bool takesRho() const;
  bool hasForm(const std::string& form) const;
};

// The law of a scene table through its entry: the key `formulation`,
// "equality" (the entry's parse) or "aft" (parse_aft), is read here for every
// law, by default "equality" where the law has it; an unknown name, or a
// formulation the law has not, is an InputError naming the field.
std::shared_ptr<Law> parseLaw(const LawEntry& entry, LawTable& table);

// The formulation parseLaw takes for `table` when it names none.
std::string defaultFormulation(const LawEntry& entry, const LawTable& table);

// The law is in its alternating frequency-time form (it has no ρ or form).
bool inAftForm(const Law& law);

// Every law, in the order they are listed to users.
const std::vector<LawEntry>& lawRegistry();
// The entry of a type; nullptr for an unknown name.
const LawEntry* findLaw(const std::string& type);
// The entry of a law instance (std::logic_error for a law never registered).
const LawEntry& lawEntry(const Law& law);
// "coulomb-1d, coulomb-2d, ...": the known types, for messages.
std::string knownLawTypes();

// Capability queries on an instance (none for a law built in code whose
// type is not registered).
std::optional<SmoothFlowSite> smoothFlowSite(const Law& law);
std::optional<PiecewiseLinearSite> piecewiseLinearSite(const Law& law);
// Whether every law is best solved on the condensed system (LawSystem).
bool suitsCondensedSystem(const std::vector<AttachedLaw>& laws);

}  // namespace eqhb
