// Space frame: straight beams along x whose nodes move in three directions
// (u along x, v along y, w along z) and turn about the three axes (θx, θy,
// θz), six DOFs per node. Each element of length ℓ is four uncoupled parts
// of a straight Euler–Bernoulli member (the usual 12-DOF frame element):
//   axial bar on (u1, u2):      K = EA/ℓ [1 −1; −1 1],  M = ρAℓ/6 [2 1; 1 2]
//   torsion on (θx1, θx2):      K = GJ/ℓ [1 −1; −1 1],  M = ρI_pℓ/6 [2 1; 1 2]
//   bending in x–y on (v, θz):  the Hermite blocks of beam.h with E I_z, θz = dv/dx
//   bending in x–z on (w, θy):  the same with E I_y, θy = −dw/dx
// with consistent mass and I_p = I_y + I_z, the polar moment of the section
// (exact for a circle or a ring; a user with another section gives its
// torsion constant J for the stiffness, which is where the two differ most).
// The rotations are the right-hand rotation vector, so (v, w) and (θy, θz)
// turn alike when the frame is turned about its axis.
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "eqhb/structures/structure_matrices.h"

namespace eqhb {

struct SpaceFrameSection {
  double youngs_modulus = 1.0;  // E
  double shear_modulus = 1.0;   // G
  double density = 1.0;         // ρ
  double area = 1.0;            // A
  double second_moment_y = 1.0; // I_y: bending in the x–z plane (w)
  double second_moment_z = 1.0; // I_z: bending in the x–y plane (v)
  double torsion_constant = 1.0;// J
};

// Adds one element of length `length` to the triplets of K and M; `dofs`
// are (u, v, w, θx, θy, θz) of its first node then of its second, −1 for a
// clamped DOF (left out).
void addSpaceFrameElement(const SpaceFrameSection& section, double length, const std::array<int, 12>& dofs,
                          std::vector<Eigen::Triplet<double>>* stiffness, std::vector<Eigen::Triplet<double>>* mass);

struct SpaceFrameParameters {
  int elements = 10;
  SpaceFrameSection section;
  double length = 1.0;  // L
};

// A cantilever space frame clamped at x = 0 (node 0 removed), free at x = L:
// component c (0..5: u, v, w, θx, θy, θz) of node i (1..n) is DOF
// spaceFrameDof(i, c). Damping left zero. Throws InputError naming the
// parameter (structure.elements, .E, .G, .rho, .A, .Iy, .Iz, .J, .L) if one is
// not positive and finite.
StructureMatrices cantileverSpaceFrame(const SpaceFrameParameters& frame);

inline int spaceFrameDof(int node, int component) { return 6 * (node - 1) + component; }

// The first `count` closed-form torsional frequencies (rad/s) of the
// continuous clamped-free shaft: ω_n = (2n − 1) π / (2L) sqrt(GJ / (ρ I_p)).
std::vector<double> torsionFrequencies(const SpaceFrameParameters& frame, int count);

}  // namespace eqhb
