// Euler–Bernoulli cantilever beam: n equal elements with Hermite cubic shape
// functions, consistent mass, clamped at x = 0 (node 0 removed), free at
// x = L. Two DOFs per node: node i (1..n, counted from the clamp) has the
// transverse displacement w at DOF 2(i−1) and the rotation θ at 2(i−1)+1
// (0-based). Element matrices (length ℓ):
//   K_e = EI/ℓ³ [12 6ℓ −12 6ℓ; 6ℓ 4ℓ² −6ℓ 2ℓ²; −12 −6ℓ 12 −6ℓ; 6ℓ 2ℓ² −6ℓ 4ℓ²]
//   M_e = ρAℓ/420 [156 22ℓ 54 −13ℓ; 22ℓ 4ℓ² 13ℓ −3ℓ²; 54 13ℓ 156 −22ℓ; −13ℓ −3ℓ² −22ℓ 4ℓ²]
#pragma once

#include <vector>

#include "eqhb/structures/structure_matrices.h"

namespace eqhb {

struct BeamParameters {
  int elements = 10;
  double youngs_modulus = 1.0;  // E
  double second_moment = 1.0;   // I
  double mass_per_length = 1.0; // ρA
  double length = 1.0;          // L
};

// Mass and stiffness of the clamped beam (damping left zero). Throws
// InputError naming the parameter if one is not positive and finite.
StructureMatrices cantileverBeam(const BeamParameters& beam);

// K_e and M_e above without their factors EI/ℓ³ and ρAℓ/420, on (w1, θ1,
// w2, θ2); the frame element (frame.h) bends by the same blocks.
struct HermiteBlocks {
  double stiffness[4][4];
  double mass[4][4];
};
HermiteBlocks hermiteBeamBlocks(double l);

// DOF (0-based) of the transverse displacement of node `node` (1..n).
inline int beamTransverseDof(int node) { return 2 * (node - 1); }

// The first `count` closed-form bending frequencies (rad/s) of the continuous
// clamped-free beam: ω_n = (β_n L)² sqrt(EI / (ρA L⁴)), cos βL cosh βL = −1.
std::vector<double> cantileverFrequencies(const BeamParameters& beam, int count);

}  // namespace eqhb
