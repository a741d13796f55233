// Factorisations of the dynamic stiffness A_k (see LinearStructure), one per
// harmonic of the basis, for the condensed system: dense partial-pivoting LU
// for small structures, UMFPACK's sparse LU (through Eigen's UmfPackSupport)
// for large ones. The sparse symbolic analysis (ordering, fill-in) is made
// once at construction; a new ω only refactors numerically.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <vector>

#include "eqhb/harmonic_balance/harmonic_set.h"
#include "eqhb/solvers/deadline.h"
#include "eqhb/sparse_matrix.h"
#include "eqhb/structures/linear_structure.h"

namespace eqhb {

class DynamicStiffnessFactors {
 public:
  // `deadline` is checked between the harmonics' symbolic analyses
  // (TimeLimitReached).
  DynamicStiffnessFactors(const LinearStructure& structure, const HarmonicSet& basis, bool sparse,
                          const Deadline& deadline = Deadline());
  ~DynamicStiffnessFactors();
  DynamicStiffnessFactors(DynamicStiffnessFactors&&) noexcept;
  DynamicStiffnessFactors& operator=(DynamicStiffnessFactors&&) noexcept;

  // Factors every A_k at ω. Throws std::runtime_error naming ω and the
  // harmonic when some A_k is singular; the factors are then unusable until
  // a factorize() succeeds.
  // `structure` is the one given at construction (or an equal copy).
  // `deadline` is checked between harmonics (TimeLimitReached).
  void factorize(const LinearStructure& structure, double omega, const Deadline& deadline = Deadline());
  // A_k⁻¹ rhs for the harmonic at index h of the basis (rhs: w n rows).
  Eigen::MatrixXd solve(int h, const Eigen::MatrixXd& rhs) const;

  bool sparse() const { return sparse_; }
  // Seconds spent in the symbolic analyses (sparse) at construction.
  double analysisSeconds() const { return analysis_seconds_; }
  // Seconds of the last factorize().
  double factorSeconds() const { return factor_seconds_; }
  // Bytes held by the numerical factors (UMFPACK's count; n² per dense LU).
  double factorBytes() const { return factor_bytes_; }

 private:
  struct Sparse;
  std::vector<int> harmonics_;
  bool sparse_;
  std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> dense_;
  std::unique_ptr<Sparse> sparse_factors_;
  double analysis_seconds_ = 0.0, factor_seconds_ = 0.0, factor_bytes_ = 0.0;
};

}  // namespace eqhb
