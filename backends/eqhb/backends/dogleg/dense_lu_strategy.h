// The dense variant of the LU step strategy (lu_dogleg_strategy.h): the
// weak Jacobian J as a dense matrix and Eigen's partial-pivoting LU of it.
// At n unknowns the LU costs ⅔ n³ flops against the 8⁄3 n³ of a Householder
// QR with its Q formed (what updating Q R needs): at n = 700, 13 ms against
// 55 ms. With the Broyden policy the model matrix is B = J + Σ uᵢ vᵢᵀ, the
// same rank-one updates as the QR strategy's (dense_dogleg_strategy.h), kept
// as vectors: B⁻¹ by Sherman–Morrison on the LU of J, B x and Bᵀ x by
// products with J and the vectors; a fresh Jacobian after two failed steps in
// a row, after kMostUpdates updates, or when an update makes B singular.
// With update = "refresh" (the default) the model before the first rejected
// step is instead the Jacobian at each accepted iterate, its Newton step by
// GMRES on the LU kept (preconditioned_gmres.h): near-Newton steps for one
// Jacobian and a few products each, where a warm-started point would take many
// secant steps; a GMRES miss takes a new LU of that Jacobian.
#pragma once

#include <Eigen/Dense>

#include "eqhb/backends/dogleg/lu_dogleg_strategy.h"
#include "eqhb/backends/dogleg/powell_dogleg.h"
#include "eqhb/backends/dogleg/preconditioned_gmres.h"

namespace eqhb::dogleg {

class DenseLuStrategy : public LuDoglegStrategy {
 public:
  // Updates kept before a fresh Jacobian: each costs two vector products per
  // step, and a long run of them means the secant model has drifted.
  static constexpr int kMostUpdates = 48;
  // Krylov vectors before a new LU: 20 products and solves cost about a
  // sixth of an LU at n = 700.
  static constexpr int kMostKrylovVectors = 20;
  // GMRES stops at ‖g − J y‖ <= this · ‖g‖: an inexact Newton step whose
  // linear error stays far below the nonlinear one.
  static constexpr double kKrylovTolerance = 1e-4;

  DenseLuStrategy(MonitoredSystem& system, JacobianPolicy policy, bool refresh);

  bool evaluateJacobian(const Eigen::VectorXd& z, Eigen::VectorXd& g, int iteration, StopReason* stop) override;
  double jacobianColumnNorm(Eigen::Index j) const override { return jacobian_.col(j).norm(); }
  bool prepareModel(const Eigen::VectorXd& g, const Eigen::VectorXd& diag, int iteration, StopReason* stop) override;
  bool keepModel(const TrialStep& trial) override;
  std::string messagePrefix() const override { return "dense LU; "; }

 private:
  bool factorise(int iteration, StopReason* stop) override;
  bool solveNewton(const Eigen::VectorXd& g, Eigen::VectorXd& newton) override;
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& bx) override;
  void multiplyTransposed(const Eigen::VectorXd& x, Eigen::VectorXd& btx) override;
  // y = B⁻¹ x: J⁻¹ x, then each update's Sherman–Morrison correction in turn.
  void applyInverse(const Eigen::VectorXd& x, Eigen::VectorXd& y);

  // The refresh model after an accepted step: J at the new iterate, its
  // Newton step by GMRES on the LU kept; false for a new LU.
  bool refreshModel(const TrialStep& trial);

  JacobianPolicy policy_;
  bool refresh_;                // the refresh model, until a step is rejected
  bool krylov_ = false;         // jacobian_ is newer than lu_'s factors
  bool refreshed_at_z_ = false;  // jacobian_ and g_: the refresh model's J and g at z_
  Eigen::VectorXd z_;            // where jacobian_ was evaluated
  Eigen::VectorXd krylov_step_;  // J⁻¹ g of the refresh model, by GMRES
  PreconditionedGmres gmres_;
  Eigen::MatrixXd jacobian_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  // Every matrix and vector of the updates is made here, once.
  int updates_ = 0;
  Eigen::MatrixXd u_, v_, inverse_u_;  // columns uᵢ, vᵢ, Bᵢ⁻¹ uᵢ (Bᵢ: before update i)
  Eigen::VectorXd inverse_scale_;      // 1 / (1 + vᵢᵀ Bᵢ⁻¹ uᵢ)
  Eigen::VectorXd g_, coefficients_, update_u_, update_v_, inverse_update_u_;
};

}  // namespace eqhb::dogleg
