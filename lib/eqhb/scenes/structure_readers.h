// The [structure] table of a scene: each structure type's reader (chain,
// inline matrices, Matrix Market files, beam, plane and space frames, lap
// joint), found by name in one table, and how elements name its nodes.
#pragma once

#include <string>
#include <vector>

#include "eqhb/harmonic_balance/system_memory.h"
#include "eqhb/scenes/table_reader.h"
#include "eqhb/structures/beam.h"
#include "eqhb/structures/linear_structure.h"
#include "eqhb/structures/node_table.h"

namespace eqhb::scene_reading {

// The structure and how its nodes map to DOFs (beams: node i's transverse
// displacement is DOF 2(i−1); other structures have no nodes).
struct ReadStructure {
  LinearStructure structure;
  int nodes = 0;
  NodeTable node_table;  // all but beams: node i + 1 → its DOFs (node_table.h)
  std::vector<std::string> dof_names;  // beams and frames: HbModel::dof_names
};

// How an element names nodes (`between`): a node table's node → its DOFs, a
// beam's node i → its transverse DOF 2(i − 1), else one node per DOF.
struct NodeMap {
  int dofs = 0;
  int beam_nodes = 0;
  const std::vector<std::vector<int>>* table = nullptr;
  int count() const {
    if (table && !table->empty()) return static_cast<int>(table->size());
    return beam_nodes > 0 ? beam_nodes : dofs;
  }
  std::vector<int> dofsOf(int node) const {  // node from 1
    if (table && !table->empty()) return (*table)[node - 1];
    return {beam_nodes > 0 ? beamTransverseDof(node) : node - 1};
  }
};

// The [structure] table of `top`: its type's reader, then its node_table
// where the type takes one; unknown keys refused naming the allowed ones.
// `settings`: the coefficients and samples of the model the structure is
// for, so that its size is bounded before anything is built.
ReadStructure readStructure(TableReader& top, const std::string& source, const ModelSizes& settings);

}  // namespace eqhb::scene_reading
