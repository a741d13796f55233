// The linear part of the dynamics (spec §1): M ẍ + C ẋ + K x = f(t) + Σ W_l λ_l,
// with f(t) a sum of harmonic loads, and its exact projection per harmonic:
// on x = a cos kωt + b sin kωt the operator is the real 2n x 2n block
//
//     A_k = [ K − (kω)² M     kω C        ]      acting on [a; b].
//           [ −kω C           K − (kω)² M ]
//
// M, C and K are stored sparse (finite-element models have a few entries per
// row); small structures convert to dense where dense algebra is faster.
#pragma once

#include <cmath>

#include <Eigen/Dense>
#include <vector>

#include "eqhb/sparse_matrix.h"

namespace eqhb {

// DOF numbering: DOF i of the structure is row/column i of M, C and K, counted
// from 0 as Eigen indexes them; every DOF index the C++ API takes or returns
// (HarmonicLoad::dof, LawAttachment, HbSolution's displacements, a DofChoice)
// is 0-based. Scene files, the command line, Python and every writer's output
// number DOFs from 1 ("x1", "dof": 1); the scene reader and the writers convert.

// One harmonic load on one DOF: cos_amplitude cos(kωt) + sin_amplitude sin(kωt).
struct HarmonicLoad {
  int dof = 0;       // 0-based, as every DOF index in C++
  int harmonic = 1;  // k >= 0
  double cos_amplitude = 0.0;
  double sin_amplitude = 0.0;
  // Its value where the fundamental's phase is θ (= ω t): a cos kθ + b sin kθ.
  double at(double theta) const {
    const double phase = harmonic * theta;
    return cos_amplitude * std::cos(phase) + sin_amplitude * std::sin(phase);
  }
};

struct LinearStructure {
  SparseMatrix mass, damping, stiffness;  // n x n
  std::vector<HarmonicLoad> loads;

  LinearStructure() = default;
  // The three matrices in the order the name gives: mass, stiffness, damping,
  // as Python's eqhb.model(mass, stiffness, damping). There is no positional
  // constructor: C and K are both n x n, so a swap would compile and run.
  // From sparse matrices (the usual way for models read from files).
  static LinearStructure fromMassStiffnessDamping(SparseMatrix mass, SparseMatrix stiffness, SparseMatrix damping,
                                                  std::vector<HarmonicLoad> loads = {});
  // From dense matrices (small inline models); exact zeros are dropped.
  static LinearStructure fromMassStiffnessDamping(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& stiffness,
                                                  const Eigen::MatrixXd& damping,
                                                  std::vector<HarmonicLoad> loads = {});

  int dofs() const { return static_cast<int>(mass.rows()); }
  // Throws InputError naming the matrix and the rule (square, same size,
  // finite, symmetric positive semidefinite mass) or the load.
  void validate() const;
  // The union of the patterns of M, C and K (values 1): where A_k may be
  // nonzero within one block, for every k and ω.
  SparseMatrix pattern() const;
  // A_k for harmonic k at frequency omega (k = 0: the n x n block K), dense.
  Eigen::MatrixXd harmonicOperator(int k, double omega) const;
  // A_k as a sparse matrix whose pattern is that of pattern() in each block
  // (explicit zeros kept), the same for every ω: a factorisation's symbolic
  // analysis made for one ω serves all others.
  SparseMatrix harmonicOperatorSparse(int k, double omega) const;
};

}  // namespace eqhb
