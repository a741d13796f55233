#include "eqhb/solvers/option_check.h"

#include "eqhb/error.h"

namespace eqhb {

namespace {

// g(z) = z: its root is the start, so a backend that takes the options
// returns at once.
class IdentitySystem final : public SquareSystem {
 public:
  int size() const override { return 2; }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override {
    g = z;
    return true;
  }
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override {
    g = z;
    jacobian.setIdentity();
    return true;
  }
};

}  // namespace

void checkSolverOptions(Solver& solver, const SolverOptions& options) {
  IdentitySystem system;
  const SolverResult r = solver.solve(system, Eigen::VectorXd::Zero(system.size()), options);
  if (r.termination == Termination::kInvalidOptions) throw InputError("options: " + r.native_message);
}

}  // namespace eqhb
