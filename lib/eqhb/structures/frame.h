// Plane frame: straight beams along x whose nodes move axially (u), across
// (w) and turn (θ = dw/dx). Each element of length ℓ is an axial bar with
// linear shape functions and an Euler–Bernoulli beam with Hermite cubics
// (the bending block of beam.h), uncoupled in a straight beam:
//   K_bar = EA/ℓ [1 −1; −1 1],   M_bar = ρAℓ/6 [2 1; 1 2]
// on (u1, u2), consistent mass. A point at height z above the axis moves
// axially by u − z θ: what a surface in contact slides by (lap_joint.h).
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "eqhb/structures/structure_matrices.h"

namespace eqhb {

struct FrameSection {
  double youngs_modulus = 1.0;   // E
  double area = 1.0;             // A
  double second_moment = 1.0;    // I
  double mass_per_length = 1.0;  // ρA
};

// Adds one element of length `length` to the triplets of K and M; `dofs`
// are (u1, w1, θ1, u2, w2, θ2), −1 for a clamped DOF (left out).
void addFrameElement(const FrameSection& section, double length, const std::array<int, 6>& dofs,
                     std::vector<Eigen::Triplet<double>>* stiffness, std::vector<Eigen::Triplet<double>>* mass);

struct FrameParameters {
  int elements = 10;
  FrameSection section;
  double length = 1.0;  // L
};

// A cantilever frame clamped at x = 0 (node 0 removed), free at x = L: node
// i (1..n) has u at DOF frameDof(i, 0), w at frameDof(i, 1), θ at
// frameDof(i, 2). Damping left zero. Throws InputError naming the parameter
// (structure.elements, .E, .A, .I, .rhoA, .L) if one is not positive and finite.
StructureMatrices cantileverFrame(const FrameParameters& frame);

// DOF (0-based) of component c (0: u, 1: w, 2: θ) of node `node` (1..n).
inline int frameDof(int node, int component) { return 3 * (node - 1) + component; }

// The first `count` closed-form axial frequencies (rad/s) of the continuous
// clamped-free bar: ω_n = (2n − 1) π / (2L) sqrt(EA / ρA).
std::vector<double> axialBarFrequencies(const FrameParameters& frame, int count);

// Throws InputError naming `field` unless x is finite and > 0.
void requirePositive(const char* field, double x);

}  // namespace eqhb
