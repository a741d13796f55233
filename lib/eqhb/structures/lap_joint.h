// Two beams bolted over a lap joint (the field's reference jointed
// structure, after the Brake–Reuss beam), as a plane frame (frame.h):
//
//   clamp ══════ upper beam ══════╗
//                     ╚═══════ lower beam ═══════ clamp
//                     |← overlap →|
//
// Each beam, of length L and solid section h x b, is clamped at its outer
// end; the upper beam lies on the lower one over the last `overlap` of its
// length, where `pairs` node pairs face each other (pair k at
// x = L − overlap + (k − 1) overlap / (pairs − 1) on both). Outside the
// overlap each beam has `elements` equal elements.
//
// The facing surfaces are h/2 from each axis: the upper beam's lower surface
// slides axially by u + (h/2) θ, the lower beam's upper surface by
// u − (h/2) θ (frame.h: u − z θ at height z). So that a contact element
// reads those motions as node displacements, the axial DOF of every overlap
// node is its facing surface's axial displacement u_s instead of u (x = T x̃,
// M̃ = Tᵀ M T, K̃ = Tᵀ K T; the rotation and transverse DOFs are kept).
#pragma once

#include <vector>

#include "eqhb/structures/node_table.h"
#include "eqhb/structures/structure_matrices.h"

namespace eqhb {

struct LapJointParameters {
  int pairs = 20;           // node pairs over the overlap, >= 2
  int elements = 10;        // elements of each beam outside the overlap, >= 1
  double length = 1.0;      // L, each beam
  double overlap = 0.2;     // 0 < overlap < L
  double thickness = 0.02;  // h
  double width = 0.02;      // b
  double youngs_modulus = 1.0;
  double density = 1.0;     // ρ (mass per volume)
};

struct LapJoint {
  StructureMatrices matrices;  // damping left zero
  // Nodes 1..pairs: the upper beam's lower surface at pair k, [u_s, w];
  // nodes pairs + 1..2 pairs: the lower beam's upper surface at pair k.
  NodeTable surfaces;
  int beam_nodes = 0;  // free nodes of each beam: elements + pairs − 1
};

// Throws InputError naming the field (structure.pairs, .elements, .L,
// .overlap, .h, .b, .E, .rho) for a parameter out of range.
LapJoint lapJoint(const LapJointParameters& p);

// DOF (0-based) of component c (0: u or u_s, 1: w, 2: θ) of node `node`
// (1..beam_nodes, counted from the clamp) of beam 0 (upper) or 1 (lower).
inline int lapJointDof(int beam_nodes, int beam, int node, int component) {
  return 3 * (beam * beam_nodes + node - 1) + component;
}

}  // namespace eqhb
