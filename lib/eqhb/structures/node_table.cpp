#include "eqhb/structures/node_table.h"

#include <fstream>
#include <map>
#include <sstream>

#include "eqhb/error.h"

namespace eqhb {

namespace {
std::string rowText(const std::vector<long long>& row) {
  std::string text = "[";
  for (size_t i = 0; i < row.size(); ++i) text += (i ? ", " : "") + std::to_string(row[i]);
  return text + "]";
}
}  // namespace

NodeTable makeNodeTable(const std::vector<std::vector<long long>>& rows, int dofs, const std::string& field) {
  NodeTable table;
  std::map<long long, size_t> owner;  // DOF → its node (index)
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::string where = field + "[" + std::to_string(i) + "]";
    const auto& row = rows[i];
    if (row.empty() || row.size() > static_cast<size_t>(kMaxNodeDofs))
      throwInputError(where, rowText(row), "a node lists 1 to " + std::to_string(kMaxNodeDofs) + " DOFs");
    std::vector<int> node;
    for (long long dof : row) {
      if (dof < 1 || dof > dofs)
        throwInputError(where, std::to_string(dof),
                        "no such DOF (the structure has " + std::to_string(dofs) + ", numbered from 1)");
      const auto [it, fresh] = owner.emplace(dof, i);
      if (!fresh)
        throwInputError(where, std::to_string(dof), "this DOF is also in node " + std::to_string(it->second + 1));
      node.push_back(static_cast<int>(dof - 1));
    }
    table.push_back(node);
  }
  return table;
}

NodeTable readNodeTable(const std::string& path, int dofs, const std::string& field) {
  std::ifstream in(path);
  if (!in) throwInputError(field, "\"" + path + "\"", "cannot open the node table");
  std::map<long long, std::vector<long long>> nodes;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = field + " (" + path + " line " + std::to_string(number) + ")";
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::vector<long long> values;
    std::string word;
    while (words >> word) {
      std::size_t used = 0;
      long long value = 0;
      try {
        value = std::stoll(word, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != word.size()) throwInputError(where, word, "must be an integer (a node, then its DOFs)");
      values.push_back(value);
    }
    if (values.empty()) continue;
    if (values.size() < 2) throwInputError(where, line, "a node needs its DOFs: `node dof [dof ...]`");
    if (nodes.size() >= static_cast<size_t>(dofs))
      throwInputError(where, line, "more nodes than DOFs (" + std::to_string(dofs) + ")");
    if (!nodes.emplace(values[0], std::vector<long long>(values.begin() + 1, values.end())).second)
      throwInputError(where, std::to_string(values[0]), "node listed twice");
  }
  if (nodes.empty()) throwInputError(field, "\"" + path + "\"", "the node table lists no node");
  std::vector<std::vector<long long>> rows;
  long long expected = 1;
  for (const auto& [id, row] : nodes) {
    if (id != expected)
      throwInputError(field, "\"" + path + "\"",
                      "nodes must be numbered 1.." + std::to_string(nodes.size()) + " (node " +
                          std::to_string(expected) + " is missing)");
    rows.push_back(row);
    ++expected;
  }
  return makeNodeTable(rows, dofs, field + " (" + path + ")");
}

}  // namespace eqhb
