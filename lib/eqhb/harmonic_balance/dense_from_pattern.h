// A Jacobian kept as values on a fixed compressed pattern, written into a
// dense matrix: how the full and mode systems serve the dense backends from
// the one sparse assembly.
#pragma once

#include <Eigen/Core>

#include "eqhb/sparse_matrix.h"

namespace eqhb {

// dense = the matrix with `pattern`'s structure and `values` (one per
// nonzero, in the pattern's storage order); every other entry zero.
inline void denseFromPattern(const SparseMatrix& pattern, const double* values, Eigen::Ref<Eigen::MatrixXd> dense) {
  dense.setZero();
  for (int j = 0; j < pattern.outerSize(); ++j)
    for (int p = pattern.outerIndexPtr()[j]; p < pattern.outerIndexPtr()[j + 1]; ++p)
      dense(pattern.innerIndexPtr()[p], j) = values[p];
}

}  // namespace eqhb
