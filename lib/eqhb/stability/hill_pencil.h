// The Hill pencil A u = s B u about a harmonic-balance solution, on
// u = [p; q; w] (hill_stability.h derives it): A = diag(J, I) with J the full
// system's weak Jacobian, B the s-terms of the dynamics (damping, mass), of
// the laws (Ψ_v, Ψ_λ̇) and of the identity rows w − s p = 0.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/sparse_matrix.h"

namespace eqhb {

// B is kept only on its nonzero columns: B = B̃ E, E picking `columns` of u.
struct HillPencil {
  SparseMatrix a, b_columns;   // A (size x size), B̃ (size x columns)
  std::vector<int> columns;    // p first, then w, then q where Ψ depends on λ̇
  int size = 0, displacement_unknowns = 0;
  int jacobian_size = 0;       // n0: A = diag(J, I) with J n0 x n0
};

// Builds the pencils of one model's solutions, point after point: what does
// not depend on the point (the full system and its Jacobian pattern, the
// Fourier transform of the law rows, the law samples, the triplet lists) is
// made once.
class HillPencilBuilder {
 public:
  // Throws InputError if the model is invalid.
  explicit HillPencilBuilder(const HbModel& model);
  // Throws InputError naming omega unless it is finite and > 0.
  void setOmega(double omega) { system_.setOmega(omega); }
  const HbModel& model() const { return system_.model(); }
  // The pencil about `full` = [x; λ] of the full system at the model's ω.
  // Throws InputError if `full` has the wrong size.
  const HillPencil& build(const Eigen::VectorXd& full);
  // J at the last build (the top-left block of A), on the full system's
  // fixed pattern.
  const SparseMatrix& jacobian() const { return jacobian_; }

 private:
  using Triplet = Eigen::Triplet<double>;
  void startPencil(const Eigen::VectorXd& full);
  void addDynamicsRates();
  // True if some law reads λ̇ (its q columns of B are then nonzero).
  bool addLawRates(const Eigen::VectorXd& full);
  void assemble(bool force_rate);

  FullSystem system_;  // its model's ω the current point's
  SparseMatrix jacobian_;
  Eigen::VectorXd g_;
  FourierTransform transform_;
  std::vector<LawSamples> law_samples_;
  Eigen::VectorXd rate_, reading_;  // reading: u_a = W_a x, coefficients
  Eigen::MatrixXd block_;
  std::vector<Triplet> a_, b_, b_kept_;
  std::vector<int> position_;  // of each column of u among the kept ones, or −1
  HillPencil pencil_;
};

}  // namespace eqhb
