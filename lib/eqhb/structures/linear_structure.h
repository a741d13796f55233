// The linear part of the dynamics (spec §1): M ẍ + C ẋ + K x = f(t) + Σ W_l λ_l,
// with f(t) a sum of harmonic loads, and its exact projection per harmonic:
// on x = a cos kωt + b sin kωt the operator is the real 2n x 2n block
//
//     A_k = [ K − (kω)² M     kω C        ]      acting on [a; b].
//           [ −kω C           K − (kω)² M ]
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace eqhb {

// One harmonic load on one DOF: cos_amplitude cos(kωt) + sin_amplitude sin(kωt).
struct HarmonicLoad {
  int dof = 0;       // 0-based
  int harmonic = 1;  // k >= 0
  double cos_amplitude = 0.0;
  double sin_amplitude = 0.0;
};

struct LinearStructure {
  Eigen::MatrixXd mass, damping, stiffness;  // n x n
  std::vector<HarmonicLoad> loads;

  int dofs() const { return static_cast<int>(mass.rows()); }
  // Throws InputError naming the matrix and the rule (square, same size,
  // finite, symmetric positive semidefinite mass) or the load.
  void validate() const;
  // A_k for harmonic k at frequency omega (k = 0: the n x n block K).
  Eigen::MatrixXd harmonicOperator(int k, double omega) const;
};

}  // namespace eqhb
