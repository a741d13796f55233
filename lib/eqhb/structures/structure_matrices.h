// Sparse M, C, K of a structure read from files or assembled from elements,
// the damping models that build C from M and K, and the checks a structure
// must pass before it becomes a LinearStructure (spec §1).
#pragma once

#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "eqhb/structures/linear_structure.h"

namespace eqhb {

struct StructureMatrices {
  Eigen::SparseMatrix<double> mass, damping, stiffness;  // n x n, symmetric
  int dofs() const { return static_cast<int>(mass.rows()); }
};

// M and K (n x n) summed from element triplets, C zero: the end of every
// element assembly (beam, frame, lap joint).
StructureMatrices fromElementTriplets(int n, const std::vector<Eigen::Triplet<double>>& mass,
                                      const std::vector<Eigen::Triplet<double>>& stiffness);

// C = α M + β K.
Eigen::SparseMatrix<double> rayleighDamping(const StructureMatrices& s, double alpha, double beta);

// Modal damping with one ratio ζ for every mode: C = M Φ diag(2 ζ ω_i) Φᵀ M
// with K Φ = M Φ Ω², Φᵀ M Φ = I (dense eigen-decomposition, so C is dense:
// meant for reduced models). Needs M positive definite; throws InputError
// naming `field` otherwise or above `max_dofs`.
Eigen::SparseMatrix<double> modalDamping(const StructureMatrices& s, double ratio, const std::string& field,
                                         int max_dofs = 3000);
// The size rule of modalDamping alone, for a structure not read yet.
void checkModalDampingSize(int dofs, double ratio, const std::string& field, int max_dofs = 3000);

// Throws InputError naming the matrix (by `names`, e.g. the file paths) if
// the three are not square and of one size, not finite, asymmetric beyond
// `symmetry_tolerance` (relative to the matrix's largest entry), if M, K or C
// has a negative direction, or if the massless DOFs (zero rows of M) are not held
// by K (K restricted to them must be regular, so that the dynamics stay a
// regular DAE and every A_k can be factorised).
struct MatrixNames {
  std::string mass = "mass", damping = "damping", stiffness = "stiffness";
};
void checkStructureMatrices(const StructureMatrices& s, double symmetry_tolerance, const MatrixNames& names);

// The structure with these matrices and no loads.
LinearStructure toLinearStructure(const StructureMatrices& s);

}  // namespace eqhb
