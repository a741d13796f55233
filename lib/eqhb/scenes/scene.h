// Scene files (problems/*.toml): a small, readable TOML description of one
// test problem — structure, loads, laws, default harmonic-balance settings —
// loaded with strict validation (unknown keys, missing keys, wrong types,
// non-physical or non-finite values are errors naming the field).
//
// Format (DOFs are numbered from 1, as in the spec):
//   name, description                          strings
//   [structure] type = "chain"                 dofs (default 2), m > 0, k >= 0, d >= 0:
//                                              M = m I, K = k T, C = d T,
//                                              T = tridiag(−1, 2, −1) with T_nn = 1
//   [structure] type = "matrices"              mass, damping, stiffness (arrays of rows)
//   [[forcing]] dof, harmonic (1), cos (0), sin (0)
//   [[preload]] dof or node, force: a static load (a bolt's), solved first as
//               a static contact problem (preload/static_contact.h) whose
//               state is the dynamic solve's operating point; it stays
//               applied as a constant load (needs set = "all")
//   [[law]]     type, dofs (one per component) or between = [node, node] with
//               normal and tangents (an element between two nodes; nodes from
//               [structure] node_table, a beam's nodes, else one per DOF), and
//               the keys of its type: each
//               law's entry in laws/registry/ declares them (LawEntry::parameters,
//               with defaults, ranges and docs; laws/law_registry.h)
//   [harmonic_balance] harmonics, set = odd|all, samples, omega
//   [sweep]     from, to  (optional)
//   [output]    dofs = [7, "w10"], peak = "w10" (each optional): the DOFs
//               the outputs show and the one defining a peak, by number
//               from 1 or name (scenes/dof_choice.h, which gives the default)
//   [time_reference]  step > 0, theta in [0.5, 1], periods >= 1,
//               periodic_tolerance > 0 (each optional): the scene's own
//               defaults for `eqhb simulate` and `compare`, where the
//               general ones do not settle (the command line overrides them)
//
// Overrides "path=value" change the document before validation: the path is
// dotted, array elements by index ("law[0].muN", or "law.muN" when there is
// one law), the value is TOML ("1.5", "\"projection\"", or a bare word taken
// as a string).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/preload/static_contact.h"
#include "eqhb/scenes/dof_choice.h"

namespace eqhb {

// A scene's defaults for the time reference (TimeOptions); unset: the general default.
struct TimeReferenceDefaults {
  std::optional<double> step, theta, periodic_tolerance;
  std::optional<int> periods;
};

struct Scene {
  std::string name;
  std::string description;
  std::string source;  // file path
  HbModel model;
  std::optional<double> sweep_from, sweep_to;
  TimeReferenceDefaults time_reference;
  // [[preload]]'s loads (harmonic 0, also among the model's loads).
  std::vector<HarmonicLoad> preload;
  // The static state under them, once solved (app::loadScene does): the
  // model's laws are then anchored at it (preload/operating_point.h).
  std::optional<StaticContactState> at_rest;
  // What the outputs show ([output], else defaultDofChoice).
  DofChoice output;
};

// Throws InputError with the file name and the field.
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {});
// Overrides "law[i].KEY=VALUE" for every law of the model that takes them:
// KEY "form" (laws having that form) or "rho" (laws having ρ), as the law
// registry (laws/law_registry.h) declares them.
std::vector<std::string> lawOverrides(const HbModel& model, const std::string& key, const std::string& value);
// The overrides "law[i].formulation=..." that set `formulation` on every law
// of `model` having it ("aft": an alternating frequency–time form, law
// registry); the others keep theirs, as a form is set only on the laws that
// have it. An unknown name, or one that no law of the scene has, is an
// InputError naming "formulation".
std::vector<std::string> lawFormulationOverrides(const HbModel& model, const std::string& formulation);

Scene parseScene(const std::string& text, const std::string& source_name,
                 const std::vector<std::string>& overrides = {});

}  // namespace eqhb
