// The one sparse matrix type of the library: column-major, int indices,
// compressed (what Eigen's SuiteSparse wrappers and the backends take).
#pragma once

#include <Eigen/SparseCore>

namespace eqhb {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Dense or sparse linear algebra. kAuto: sparse from a size up, where the
// sparse factorisations overtake the dense ones.
enum class LinearAlgebra { kAuto, kDense, kSparse };
// Solvers: unknowns of the square system from which kAuto goes sparse.
constexpr int kSparseFromUnknowns = 500;
// Condensation: DOFs of the structure from which kAuto factors A_k sparse.
constexpr int kSparseCondensationFromDofs = 100;

}  // namespace eqhb
