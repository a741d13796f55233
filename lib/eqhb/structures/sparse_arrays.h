// Sparse matrices handed over as raw arrays by another program (scipy's CSC,
// CSR and COO layouts, as the Python module receives them). Such arrays may
// legally hold duplicate entries (to be summed) and unsorted row indices, and
// may be corrupt (indices out of range, a non-monotone indptr). Every array
// is checked against every other before anything is read through it, so bad
// input ends in an InputError naming `field`, never in a read out of bounds;
// the result is canonical (sorted, duplicates summed, compressed).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "eqhb/sparse_matrix.h"

namespace eqhb {

// A read-only view of one array owned by the caller.
template <typename T>
struct ArrayView {
  const T* data = nullptr;
  std::size_t size = 0;
  const T& operator[](std::size_t i) const { return data[i]; }
};
using IndexView = ArrayView<std::int64_t>;
using ValueView = ArrayView<double>;

// Throws InputError naming `field` unless a rows x cols sparse matrix of
// `entries` stored entries fits Eigen's int indices and the size limit
// (sparseBytes, kMaxModelBytes). Called before anything is allocated.
void checkSparseSize(const std::string& field, std::int64_t rows, std::int64_t cols, std::int64_t entries);

// Compressed sparse columns (CSC): column j holds the entries
// k = indptr[j] .. indptr[j+1]-1, at row indices[k] with value values[k].
// indptr has cols + 1 entries, starts at 0 and never decreases; indices and
// values may be longer than indptr[cols] (the rest is unused, as in scipy).
// Row indices must lie in 0 .. rows-1 and values must be finite.
// kRows (CSR): the same with the roles of rows and columns exchanged.
enum class Compressed { kColumns, kRows };
SparseMatrix sparseFromCompressed(const std::string& field, Compressed layout, std::int64_t rows, std::int64_t cols,
                                  IndexView indptr, IndexView indices, ValueView values);

// Coordinates: entry k at (row[k], col[k]) with value values[k]; the three
// arrays have one length. Same rules for the indices and values.
SparseMatrix sparseFromCoordinates(const std::string& field, std::int64_t rows, std::int64_t cols, IndexView row,
                                   IndexView col, ValueView values);

}  // namespace eqhb
