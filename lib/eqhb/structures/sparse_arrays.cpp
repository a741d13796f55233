#include "eqhb/structures/sparse_arrays.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/size_limits.h"

namespace eqhb {

namespace {

constexpr std::int64_t kMaxIndex = std::numeric_limits<int>::max();

std::string shapeText(std::int64_t rows, std::int64_t cols) {
  return std::to_string(rows) + " x " + std::to_string(cols);
}

void checkIndicesInRange(const std::string& field, std::int64_t bound, IndexView index, std::size_t used,
                         const char* what) {
  for (std::size_t k = 0; k < used; ++k)
    if (index[k] < 0 || index[k] >= bound)
      throw InputError(field + ": stored entry " + std::to_string(k) + " has " + what + " " +
                       std::to_string(index[k]) + ", outside 0 .. " + std::to_string(bound - 1) +
                       " (index out of range)");
}

void checkFinite(const std::string& field, ValueView values, std::size_t used) {
  for (std::size_t k = 0; k < used; ++k)
    if (!std::isfinite(values[k]))
      throw InputError(field + ": stored entry " + std::to_string(k) + " is NaN or Inf");
}

// The canonical matrix of already validated compressed columns: each
// column's rows sorted, duplicates summed in the order given. Offsets and
// Indices: anything indexable (the caller's views or our own int vectors).
template <typename Offsets, typename Indices>
SparseMatrix canonical(const std::string& field, std::int64_t rows, std::int64_t cols, const Offsets& indptr,
                       const Indices& indices, ValueView values) {
  std::vector<int> outer(static_cast<std::size_t>(cols) + 1, 0), inner;
  std::vector<double> merged;
  inner.reserve(static_cast<std::size_t>(indptr[cols]));
  merged.reserve(static_cast<std::size_t>(indptr[cols]));
  std::vector<std::pair<int, double>> column;
  for (std::int64_t j = 0; j < cols; ++j) {
    column.clear();
    for (std::int64_t k = indptr[j]; k < indptr[j + 1]; ++k)
      column.emplace_back(static_cast<int>(indices[k]), values[k]);
    std::stable_sort(column.begin(), column.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    const std::size_t first = inner.size();
    for (const auto& [row, value] : column) {
      if (inner.size() > first && inner.back() == row) {
        merged.back() += value;
      } else {
        inner.push_back(row);
        merged.push_back(value);
      }
    }
    outer[j + 1] = static_cast<int>(inner.size());
  }
  for (std::int64_t j = 0; j < cols; ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k)
      if (!std::isfinite(merged[k]))
        throw InputError(field + ": the duplicate entries at (" + std::to_string(inner[k] + 1) + ", " +
                         std::to_string(j + 1) + ") sum to Inf");
  const Eigen::Map<const SparseMatrix> map(static_cast<int>(rows), static_cast<int>(cols),
                                           static_cast<int>(inner.size()), outer.data(), inner.data(),
                                           merged.data());
  return SparseMatrix(map);
}

}  // namespace

void checkSparseSize(const std::string& field, std::int64_t rows, std::int64_t cols, std::int64_t entries) {
  if (rows < 0 || cols < 0 || rows > kMaxIndex || cols > kMaxIndex)
    throw InputError(field + ": shape " + shapeText(rows, cols) + " is outside 0 .. " + std::to_string(kMaxIndex) +
                     " per dimension");
  if (entries < 0 || entries > kMaxIndex)
    throw InputError(field + ": " + std::to_string(entries) + " stored entries, more than " +
                     std::to_string(kMaxIndex));
  checkBytes(field, shapeText(rows, cols) + " with " + std::to_string(entries) + " stored entries",
             "the sparse matrix", sparseBytes(static_cast<double>(std::max(rows, cols)), static_cast<double>(entries)));
}

SparseMatrix sparseFromCompressed(const std::string& field, Compressed layout, std::int64_t rows, std::int64_t cols,
                                  IndexView indptr, IndexView indices, ValueView values) {
  checkSparseSize(field, rows, cols, 0);
  // CSR is the CSC of the transpose: `major` runs over what indptr indexes.
  const bool by_rows = layout == Compressed::kRows;
  const std::string major = by_rows ? "row" : "column";
  const std::int64_t majors = by_rows ? rows : cols, minors = by_rows ? cols : rows;
  if (indptr.size != static_cast<std::size_t>(majors) + 1)
    throw InputError(field + ": indptr has " + std::to_string(indptr.size) + " entries, a matrix of " +
                     std::to_string(majors) + " " + major + "s needs " + std::to_string(majors + 1));
  if (indptr[0] != 0) throw InputError(field + ": indptr must start at 0 (it starts at " + std::to_string(indptr[0]) + ")");
  for (std::int64_t j = 0; j < majors; ++j)
    if (indptr[j + 1] < indptr[j])
      throw InputError(field + ": indptr decreases from " + std::to_string(indptr[j]) + " to " +
                       std::to_string(indptr[j + 1]) + " at " + major + " " + std::to_string(j) +
                       " (must not decrease)");
  const std::int64_t used = indptr[majors];
  if (static_cast<std::uint64_t>(used) > indices.size || static_cast<std::uint64_t>(used) > values.size)
    throw InputError(field + ": indptr ends at " + std::to_string(used) + " but there are only " +
                     std::to_string(indices.size) + " indices and " + std::to_string(values.size) + " values");
  checkSparseSize(field, rows, cols, used);
  checkIndicesInRange(field, minors, indices, static_cast<std::size_t>(used), by_rows ? "column index" : "row index");
  checkFinite(field, values, static_cast<std::size_t>(used));
  SparseMatrix m = canonical(field, minors, majors, indptr, indices, values);
  if (by_rows) return SparseMatrix(m.transpose());
  return m;
}

SparseMatrix sparseFromCoordinates(const std::string& field, std::int64_t rows, std::int64_t cols, IndexView row,
                                   IndexView col, ValueView values) {
  if (row.size != col.size || row.size != values.size)
    throw InputError(field + ": " + std::to_string(row.size) + " row indices, " + std::to_string(col.size) +
                     " column indices and " + std::to_string(values.size) + " values (must be as many)");
  const std::size_t n = row.size;
  checkSparseSize(field, rows, cols, static_cast<std::int64_t>(n));
  checkIndicesInRange(field, rows, row, n, "row index");
  checkIndicesInRange(field, cols, col, n, "column index");
  checkFinite(field, values, n);
  // To compressed columns (entries of a column in the order given), then
  // canonical; n and every index fit int after the checks above.
  std::vector<int> indptr(static_cast<std::size_t>(cols) + 1, 0), indices(n);
  std::vector<double> ordered(n);
  for (std::size_t k = 0; k < n; ++k) ++indptr[col[k] + 1];
  for (std::int64_t j = 0; j < cols; ++j) indptr[j + 1] += indptr[j];
  std::vector<int> next(indptr.begin(), indptr.end() - 1);
  for (std::size_t k = 0; k < n; ++k) {
    const int at = next[col[k]]++;
    indices[at] = static_cast<int>(row[k]);
    ordered[at] = values[k];
  }
  return canonical(field, rows, cols, indptr, indices, ValueView{ordered.data(), n});
}

}  // namespace eqhb
