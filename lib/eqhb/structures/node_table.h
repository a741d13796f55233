// A structure's node table: node → its DOFs, so that elements between two
// bodies name nodes (their translations along x, y, z) instead of DOF
// numbers. Matrix Market files carry no geometry; the table comes with them,
// inline in the scene or as a text file of lines `node dof [dof ...]`
// (1-based, `#` starts a comment).
#pragma once

#include <string>
#include <vector>

namespace eqhb {

// Node i + 1 → its DOFs, 0-based.
using NodeTable = std::vector<std::vector<int>>;

// The most DOFs a node may list (three translations and three rotations).
inline constexpr int kMaxNodeDofs = 6;

// From rows of 1-based DOF numbers (row i is node i + 1). Throws InputError
// naming `field` (and the row) for a DOF outside 1..dofs, a DOF in two
// nodes, or a node of no or more than kMaxNodeDofs DOFs.
NodeTable makeNodeTable(const std::vector<std::vector<long long>>& rows, int dofs, const std::string& field);

// From a file of lines `node dof [dof ...]`, nodes numbered 1..N, each once,
// in any order; the same checks, naming the file and line.
NodeTable readNodeTable(const std::string& path, int dofs, const std::string& field);

}  // namespace eqhb
