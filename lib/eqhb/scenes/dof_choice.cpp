#include "eqhb/scenes/dof_choice.h"

#include <algorithm>
#include <cctype>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"

namespace eqhb {

namespace {

// "w7" -> 7 when `name` is `prefix` followed by digits only, else 0.
int numberAfter(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  for (size_t i = prefix.size(); i < name.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return 0;
  return name.size() - prefix.size() > 9 ? 0 : std::stoi(name.substr(prefix.size()));
}

bool allDigits(const std::string& token) {
  return !token.empty() && token.size() < 10 &&
         std::all_of(token.begin(), token.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

}  // namespace

DofChoice defaultDofChoice(const HbModel& model) {
  const int dofs = model.structure.dofs();
  DofChoice choice;
  std::vector<int> candidates;  // the DOFs the shown ones are spread over, in order
  std::vector<std::pair<int, int>> by_node;
  for (int i = 0; i < static_cast<int>(model.dof_names.size()) && i < dofs; ++i)
    if (const int node = numberAfter(model.dof_names[i], "w")) by_node.push_back({node, i});
  std::sort(by_node.begin(), by_node.end());
  for (const auto& [node, dof] : by_node) candidates.push_back(dof);
  if (candidates.empty()) {
    choice.peak = std::max(dofs - 1, 0);
    for (int i = 0; i < dofs; ++i) candidates.push_back(i);
    if (dofs <= kEveryDofShownUpTo) {
      choice.shown = candidates;
      return choice;
    }
  }
  // A quarter, half, three quarters along and the end (fewer on a short structure).
  const int n = static_cast<int>(candidates.size());
  for (int quarter = 1; quarter <= 4; ++quarter) {
    const int at = (quarter * n + 3) / 4 - 1;
    if (choice.shown.empty() || choice.shown.back() != candidates[at]) choice.shown.push_back(candidates[at]);
  }
  choice.peak = candidates.back();
  return choice;
}

std::vector<std::string> shownLabels(const HbModel& model, const DofChoice& choice) {
  std::vector<std::string> labels;
  for (int dof : choice.shown) labels.push_back(dofLabel(model, dof));
  return labels;
}

std::string shownDofsNote(const HbModel& model, const DofChoice& choice) {
  const int dofs = model.structure.dofs();
  bool every = static_cast<int>(choice.shown.size()) == dofs;
  for (int i = 0; every && i < dofs; ++i) every = choice.shown[i] == i;
  if (every) return "";
  std::string note;
  for (const std::string& label : shownLabels(model, choice)) note += (note.empty() ? "" : ", ") + label;
  return note + " of " + std::to_string(dofs) + " DOFs shown; others by --show or [output] dofs, by number or name" +
         (model.dof_names.empty() ? "" : " (\"" + dofLabel(model, 0) + "\")");
}

int resolveDof(const HbModel& model, const std::string& token, const std::string& field) {
  const int dofs = model.structure.dofs();
  int dof = -1;
  if (allDigits(token)) dof = std::stoi(token) - 1;
  else if (const int x = numberAfter(token, "x")) dof = x - 1;
  else
    for (int i = 0; i < dofs && dof < 0; ++i)
      if (dofLabel(model, i) == token) dof = i;
  if (dof < 0 && !allDigits(token) && !numberAfter(token, "x"))
    throwInputError(field, "\"" + token + "\"",
                    "no DOF of the structure is named so (a DOF number from 1, \"x<number>\"" +
                        std::string(model.dof_names.empty() ? "" : ", or a name such as \"" + dofLabel(model, 0) + "\"") +
                        ")");
  if (dof < 0 || dof >= dofs)
    throwInputError(field, "\"" + token + "\"",
                    "no such DOF (the structure has " + std::to_string(dofs) + ", numbered from 1)");
  return dof;
}

std::vector<int> resolveDofs(const HbModel& model, const std::vector<std::string>& tokens, const std::string& field) {
  if (tokens.empty()) throwInputError(field, "[]", "give at least one DOF");
  std::vector<int> dofs;
  for (size_t i = 0; i < tokens.size(); ++i) {
    const int dof = resolveDof(model, tokens[i], field + "[" + std::to_string(i) + "]");
    if (std::find(dofs.begin(), dofs.end(), dof) != dofs.end())
      throwInputError(field + "[" + std::to_string(i) + "]", "\"" + tokens[i] + "\"", "names a DOF given before");
    dofs.push_back(dof);
  }
  return dofs;
}

}  // namespace eqhb
