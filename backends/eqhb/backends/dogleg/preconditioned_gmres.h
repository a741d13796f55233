// GMRES on J y = b, right-preconditioned by the LU of an earlier Jacobian
// (Saad and Schultz, SIAM J. Sci. Stat. Comput. 7, 1986): J M⁻¹ u = b,
// y = M⁻¹ u, started from the chord solution y₀ = M⁻¹ b. When J differs from
// the factorised M in a few rows (the laws whose samples changed between
// stick and slip), J M⁻¹ is the identity plus a low-rank term and a few
// products with J and solves on M give the Newton step of the fresh J: a
// Newton step for a product and two triangular solves per Krylov vector
// instead of a new O(n³) factorisation. Every vector is made once, here.
#pragma once

#include <Eigen/Dense>

namespace eqhb::dogleg {

class PreconditionedGmres {
 public:
  PreconditionedGmres(Eigen::Index n, int most_vectors);

  // y with ‖b − J y‖ <= tolerance · ‖b‖, J and the LU of M as given; false
  // when `most_vectors` Krylov vectors do not get there (y then the best
  // found). Allocates nothing.
  bool solve(const Eigen::MatrixXd& jacobian, const Eigen::PartialPivLU<Eigen::MatrixXd>& preconditioner,
             const Eigen::VectorXd& b, double tolerance, Eigen::VectorXd& y);
  // Krylov vectors of the last solve (0 when the chord solution sufficed).
  int lastVectors() const { return last_vectors_; }

 private:
  int most_vectors_;
  int last_vectors_ = 0;
  Eigen::MatrixXd basis_;       // Arnoldi vectors v₁ … v_{m+1}
  Eigen::MatrixXd hessenberg_;  // (m+1) × m, made upper triangular by rotations
  Eigen::VectorXd cosines_, sines_, rhs_, coefficients_;
  Eigen::VectorXd residual_, preconditioned_, product_;
};

}  // namespace eqhb::dogleg
