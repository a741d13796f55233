// Which DOFs the outputs show (the text tables, the CSV columns, the chart's
// curves) and which one defines a curve's peak. A scene chooses them in
// [output] (dofs = [...], peak = ...), every interface may override them
// (app::SceneSettings' show and peak_dof). Without a choice a structure whose
// nodes deflect (beams, frames: DOFs named "w<node>") shows the deflection
// of four nodes spread along it up to the last, whose deflection defines the
// peak: a beam's rotations are slopes, not amplitudes to read a resonance
// from, and 120 curves hide the 4 that matter. Any other structure of up to
// kEveryDofShownUpTo DOFs shows every DOF; a larger one (a Matrix Market
// model) four DOFs spread along its numbering up to the last, for the same
// reason. Its last DOF defines the peak.
#pragma once

#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb {

struct DofChoice {
  std::vector<int> shown;  // 0-based, in the order given
  int peak = 0;            // 0-based
};

// Names per DOF for a structure of `nodes` nodes whose node i (1..nodes) has
// component c at DOF dof(i, c): `components[c]` followed by the node
// ("w7", "theta7"); DOFs of no node keep "x<i>".
template <typename DofOf>
std::vector<std::string> nodeDofNames(int dofs, int nodes, const std::vector<std::string>& components, DofOf dof) {
  std::vector<std::string> names(dofs);
  for (int i = 0; i < dofs; ++i) names[i] = "x" + std::to_string(i + 1);
  for (int node = 1; node <= nodes; ++node)
    for (size_t c = 0; c < components.size(); ++c) {
      const int d = dof(node, static_cast<int>(c));
      if (d >= 0 && d < dofs) names[d] = components[c] + std::to_string(node);
    }
  return names;
}

constexpr int kEveryDofShownUpTo = 8;

DofChoice defaultDofChoice(const HbModel& model);

// The names of the shown DOFs, in order (dofLabel, hb_solution.h).
std::vector<std::string> shownLabels(const HbModel& model, const DofChoice& choice);
// "" when `choice` shows every DOF in order; else which DOFs are shown, of
// how many, and how to pick others ("w15, w30, w45, w60 of 120 DOFs shown;
// others by --show or [output] dofs, by number or name").
std::string shownDofsNote(const HbModel& model, const DofChoice& choice);

// A DOF by its number from 1 ("7") or its name: the model's ("w7",
// "theta7") or "x7" on any structure. Throws InputError naming `field` for
// anything else or a DOF outside the structure.
int resolveDof(const HbModel& model, const std::string& token, const std::string& field);
// Each of `tokens` by resolveDof ("field[i]" in the message); an empty list
// or a DOF given twice is an InputError naming `field`.
std::vector<int> resolveDofs(const HbModel& model, const std::vector<std::string>& tokens, const std::string& field);

}  // namespace eqhb
