// The stiffness pattern of a chain of n DOFs (spec §4: k [[2, −1], [−1, 1]]
// for two): T = tridiag(−1, 2, −1) with the last diagonal entry 1, a chain
// fixed at DOF 1's left end and free after DOF n. A chain scene's K = k T,
// C = d T, M = m I.
#pragma once

#include <vector>

#include "eqhb/sparse_matrix.h"

namespace eqhb {

inline SparseMatrix chainPattern(int n) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, i + 1 < n ? 2.0 : 1.0);
    if (i + 1 < n) {
      entries.emplace_back(i, i + 1, -1.0);
      entries.emplace_back(i + 1, i, -1.0);
    }
  }
  SparseMatrix t(n, n);
  t.setFromTriplets(entries.begin(), entries.end());
  return t;
}

}  // namespace eqhb
