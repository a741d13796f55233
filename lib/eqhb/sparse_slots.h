// Where an entry lives in a compressed column-major pattern: how systems
// that assemble a Jacobian on a fixed pattern find, once at set-up, the
// value slot each term writes to.
#pragma once

#include <algorithm>
#include <stdexcept>

#include "eqhb/sparse_matrix.h"

namespace eqhb {

// Index of entry (row, col) in m's values; throws std::logic_error when the
// pattern lacks it (a set-up error, never a property of the input).
inline int slotOf(const SparseMatrix& m, int row, int col) {
  const int* begin = m.innerIndexPtr() + m.outerIndexPtr()[col];
  const int* end = m.innerIndexPtr() + m.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  if (it == end || *it != row) throw std::logic_error("sparse Jacobian: entry outside the pattern");
  return static_cast<int>(it - m.innerIndexPtr());
}

}  // namespace eqhb
