// The assembly shared by the cantilever frames (frame.h, space_frame.h):
// `elements` equal elements along x, node 0 clamped at x = 0, node i
// (1..elements) carrying DOFs PerNode (i − 1) .. PerNode i − 1.
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "eqhb/structures/structure_matrices.h"

namespace eqhb {

// M and K of the cantilever: add(dofs, &k, &m) adds the element whose two
// nodes' DOFs are `dofs` (the first node's PerNode, then the second's; −1 at
// the clamp) to the triplets, `entries_per_element` of them at most.
template <int PerNode, typename AddElement>
StructureMatrices assembleCantilever(int elements, int entries_per_element, AddElement add) {
  std::vector<Eigen::Triplet<double>> k, m;
  k.reserve(static_cast<size_t>(entries_per_element) * elements);
  m.reserve(static_cast<size_t>(entries_per_element) * elements);
  for (int e = 0; e < elements; ++e) {
    // Element e joins node e (the clamp when e = 0) and node e + 1.
    std::array<int, 2 * PerNode> dofs;
    for (int c = 0; c < PerNode; ++c) {
      dofs[c] = e == 0 ? -1 : PerNode * (e - 1) + c;
      dofs[PerNode + c] = PerNode * e + c;
    }
    add(dofs, &k, &m);
  }
  return fromElementTriplets(PerNode * elements, m, k);
}

}  // namespace eqhb
