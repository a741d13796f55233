// Powell's hybrid method with a scaled dogleg trust region, in the class of
// MINPACK's hybrj (Moré, Garbow, Hillstrom, "User guide for MINPACK-1",
// ANL-80-74, 1980): QR of the Jacobian, column-norm scaling, trust-radius
// updates from the actual/predicted reduction ratio, Broyden rank-1 updates
// of the factorisation between Jacobian evaluations, and a fresh Jacobian
// after two failed steps or when progress stalls.
//
// Two Jacobian policies:
//   kBroyden        hybrj: weak Jacobian only when needed, Broyden otherwise
//   kEveryIteration "Newton-dogleg": the weak Jacobian at every new iterate
//
// Backend options (SolverOptions::backend):
//   factor   initial trust radius = factor · ‖D z0‖ (factor if z0 = 0); > 0, default 100
//   xtol     stop when radius <= xtol · ‖D z‖ (step_tolerance); >= 0, default 1e-14
//   scaling  "columns" (D from Jacobian column norms, MINPACK mode 1) or "none"
//   factorisation  "qr", "lu" or "auto" (default): how the dense model is
//            factorised. QR is hybrj's (its Q updated by Givens rotations);
//            LU costs a quarter of a QR with its Q, and its Broyden updates
//            are kept as vectors (dense_lu_strategy.h). The steps are the
//            same in exact arithmetic; auto takes LU from kDenseLuFromUnknowns.
//   update   "refresh" (default) or "broyden": the LU's model between
//            factorisations (dense_lu_strategy.h): the Jacobian at each
//            accepted iterate solved by GMRES on the LU kept, or Broyden's
//            updates as hybrj's. The QR factorisation always updates by Broyden.
#pragma once

#include "eqhb/solvers/named_solver.h"

namespace eqhb {

enum class JacobianPolicy { kBroyden, kEveryIteration };

// From this many unknowns the dense dogleg factorises by LU: there the
// Jacobian's QR and Q (8⁄3 n³ flops) dominate a step; the LU (⅔ n³) takes a
// quarter of their time, and the sweeps of the lap joint (630 unknowns) and
// beam-joint-large (700) took 37 % and 42 % of theirs with it.
constexpr int kDenseLuFromUnknowns = 256;

class PowellDogleg : public NamedSolver {
 public:
  explicit PowellDogleg(JacobianPolicy policy)
      : NamedSolver(policy == JacobianPolicy::kBroyden
                        ? SolverVariant{"dogleg",
                                        "own Powell hybrid dogleg (hybrj class): Broyden updates between weak "
                                        "Jacobians; dense QR, LU from 256 unknowns"}
                        : SolverVariant{"dogleg-newton",
                                        "own Powell dogleg with the weak Jacobian at every iterate (Newton-dogleg); "
                                        "dense QR, LU from 256 unknowns"}),
        policy_(policy) {}

 protected:
  void run(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
           SolverResult& result) override;

 private:
  JacobianPolicy policy_;
};

// Work vectors of doglegStep, sized once per problem.
struct DoglegWorkspace {
  explicit DoglegWorkspace(Eigen::Index n)
      : gauss_newton(n), scaled_newton(n), gradient(n), direction(n), unscaled(n), image(n), cauchy(n),
        difference(n) {}
  Eigen::VectorXd gauss_newton, scaled_newton, gradient, direction, unscaled, image, cauchy, difference;
};

// The dogleg step in scaled variables y = D p for the model ‖qtf + R p‖
// (J = Q R, qtf = Qᵀ g) inside ‖D p‖ <= radius, into `step` (no allocation).
void doglegStep(const Eigen::MatrixXd& r, const Eigen::VectorXd& diag, const Eigen::VectorXd& qtf,
                double radius, DoglegWorkspace& workspace, Eigen::VectorXd& step);
// The same, allocating (tests).
Eigen::VectorXd doglegStep(const Eigen::MatrixXd& r, const Eigen::VectorXd& diag,
                           const Eigen::VectorXd& qtf, double radius);

// Re-triangularises Q R + u vᵀ in place by Givens rotations (O(n²)),
// rotating qtf alongside so that it stays Qᵀ g; u is overwritten.
void rankOneUpdate(Eigen::MatrixXd& q, Eigen::MatrixXd& r, Eigen::VectorXd& qtf,
                   Eigen::VectorXd& u, const Eigen::VectorXd& v);

}  // namespace eqhb
