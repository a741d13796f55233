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

// Lines longer than this are refused as they are read (the format itself
// limits them to 1024 characters), so that one endless line costs nothing.
inline constexpr long kMaxMatrixMarketLine = 4096;

// What a file's header and size line declare, read without its entries.
struct MatrixMarketSize {
  long rows = 0, cols = 0;
  // Coordinate: the entry count of the size line. Array: 0 here (rows x cols
  // may overflow a long until the sizes are bounded by memory).
  long entries = 0;
  bool coordinate = true, symmetric = false;
  long size_line = 0;  // its line number, for messages
  // Entries the matrix may store once symmetric storage is expanded.
  double storedEntries() const;
  // Bytes of the compressed matrix readMatrixMarket returns, and the peak of
  // reading it: the triplet list, the transposed copy and index vectors
  // setFromTriplets builds, and that matrix.
  double matrixBytes() const;
  double readBytes() const;
};

// Reads and checks the header and the size line only: sizes positive, a
// symmetric matrix square. The sizes are not bounded yet: see below.
MatrixMarketSize readMatrixMarketSize(const std::string& path);

// Throws InputError "PATH:LINE: a R x C matrix of ... needs about X GiB to
// read, more than the 4 GiB limit" when readBytes() + extra_bytes exceeds
// kMaxModelBytes. Every allocation of readMatrixMarket is bounded by what
// this accepts; it also keeps rows, cols and rows x cols far inside int.
void checkMatrixMarketMemory(const std::string& path, const MatrixMarketSize& size, double extra_bytes = 0.0);

// Reads a real matrix; symmetric storage is expanded to both triangles.
// Duplicate coordinate entries are summed (the FE assembly convention).
Eigen::SparseMatrix<double> readMatrixMarket(const std::string& path);

// Reads a real vector: an n x 1 (or 1 x n) matrix in either layout, refused
// by its size line alone when it is not one.
Eigen::VectorXd readMatrixMarketVector(const std::string& path);

// Writes a matrix in coordinate real general form (full precision), or, when
// `symmetric`, only its lower triangle with the symmetric field.
void writeMatrixMarket(const std::string& path, const Eigen::SparseMatrix<double>& matrix,
                       bool symmetric);

// Largest |A_ij − A_ji| relative to the largest |A_ij| (0 for a zero matrix).
double relativeAsymmetry(const Eigen::SparseMatrix<double>& matrix);

}  // namespace eqhb
