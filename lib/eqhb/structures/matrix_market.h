// Matrix Market files (NIST exchange format, math.nist.gov/MatrixMarket) for
// the finite-element matrices of a structure: the mass, stiffness and damping
// matrices exported by an FE code, and load vectors.
//
// Accepted: "%%MatrixMarket matrix coordinate real|integer general|symmetric"
// and "%%MatrixMarket matrix array real|integer general|symmetric" (dense,
// column-major). Indices are 1-based, as in the format. Every problem is an
// InputError "FILE:LINE: rule" (or "FILE: rule" for whole-file rules).
//
// Eigen's unsupported loadMarket was weighed and not used: it ignores the
// symmetric storage field (half a matrix would load silently), prints bad lines
// to stderr and goes on, and cannot say which line is wrong.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <string>

namespace eqhb {

// Reads a real matrix; symmetric storage is expanded to both triangles.
// Duplicate coordinate entries are summed (the FE assembly convention).
Eigen::SparseMatrix<double> readMatrixMarket(const std::string& path);

// Reads a real vector: an n x 1 (or 1 x n) matrix in either layout.
Eigen::VectorXd readMatrixMarketVector(const std::string& path);

// Writes a matrix in coordinate real general form (full precision), or, when
// `symmetric`, only its lower triangle with the symmetric field.
void writeMatrixMarket(const std::string& path, const Eigen::SparseMatrix<double>& matrix,
                       bool symmetric);

// Largest |A_ij − A_ji| relative to the largest |A_ij| (0 for a zero matrix).
double relativeAsymmetry(const Eigen::SparseMatrix<double>& matrix);

}  // namespace eqhb
