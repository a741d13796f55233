#include "eqhb/backends/dogleg/sparse_newton_dogleg.h"

#include <Eigen/UmfPackSupport>

#include "eqhb/backends/dogleg/lu_dogleg_strategy.h"

namespace eqhb {

namespace {

using dogleg::StopReason;
using dogleg::TrialStep;

// The sparse step strategy: the Jacobian on the system's pattern and
// UMFPACK's LU of it (a singular J leaves only the gradient direction).
class SparseNewtonStrategy : public dogleg::LuDoglegStrategy {
 public:
  explicit SparseNewtonStrategy(MonitoredSystem& system)
      : LuDoglegStrategy(system), jacobian_(system.jacobianPattern()) {}

  bool evaluateJacobian(const Eigen::VectorXd& z, Eigen::VectorXd& g, int iteration, StopReason* stop) override {
    if (!system().residualAndSparseJacobian(z, g, jacobian_)) {
      *stop = {Termination::kEvaluationFailed, -1, "Jacobian evaluation failed"};
      return false;
    }
    return withinTime("Jacobian evaluation", iteration, stop);
  }

  double jacobianColumnNorm(Eigen::Index j) const override { return jacobian_.col(j).norm(); }

  std::string messagePrefix() const override { return "sparse LU (UMFPACK); "; }

 private:
  // The symbolic analysis once, on the first Jacobian's values; the numeric
  // factorisation of every Jacobian.
  bool factorise(int iteration, StopReason* stop) override {
    if (!analyzed_) {
      lu_.analyzePattern(jacobian_);
      analyzed_ = true;
      if (!withinTime("symbolic factorisation", iteration, stop)) return false;
    }
    lu_.factorize(jacobian_);
    return withinTime("numeric factorisation", iteration, stop);
  }

  bool solveNewton(const Eigen::VectorXd& g, Eigen::VectorXd& newton) override {
    if (lu_.info() != Eigen::Success) return false;
    newton = lu_.solve(g);
    return lu_.info() == Eigen::Success;
  }

  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& jx) override { jx.noalias() = jacobian_ * x; }
  void multiplyTransposed(const Eigen::VectorXd& x, Eigen::VectorXd& jtx) override {
    jtx.noalias() = jacobian_.transpose() * x;
  }

  SparseMatrix jacobian_;
  Eigen::UmfPackLU<SparseMatrix> lu_;
  bool analyzed_ = false;
};

}  // namespace

void runSparseNewtonDogleg(MonitoredSystem& system, const Eigen::VectorXd& z0,
                           const SolverOptions& options, const DoglegSettings& settings,
                           SolverResult& result) {
  SparseNewtonStrategy strategy(system);
  dogleg::runTrustRegionLoop(system, z0, options, settings, strategy, result);
}

}  // namespace eqhb
