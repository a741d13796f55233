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
// Measured on generated chains, the sparse Newton-dogleg overtakes the dense
// Broyden dogleg in time from about 120 unknowns; but on the shipped scenes of
// 120 to 210 unknowns (contact, friction-2d, damper) it stops not_progressing
// from rest where the dense path converges, so the dense path is kept up to
// here for its robustness.
constexpr int kSparseFromUnknowns = 500;
// Condensation: DOFs of the structure from which kAuto factors A_k sparse.
// Measured crossover of the set-up time (factorisations and receptance at the
// law DOFs), dense LU vs UMFPACK, on chains: between 30 and 50 DOFs.
constexpr int kSparseCondensationFromDofs = 40;

}  // namespace eqhb
