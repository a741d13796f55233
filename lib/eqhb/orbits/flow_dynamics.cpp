#include "eqhb/orbits/flow_dynamics.h"

#include <algorithm>
#include <cmath>

#include "eqhb/error.h"

namespace eqhb::orbits {

Eigen::MatrixXd invertPositiveDefiniteMass(const LinearStructure& structure) {
  const int n = structure.dofs();
  const Eigen::LLT<Eigen::MatrixXd> mass_factor{Eigen::MatrixXd(structure.mass)};
  if (mass_factor.info() != Eigen::Success || mass_factor.matrixL().toDenseMatrix().diagonal().minCoeff() <= 0.0)
    throwInputError("structure.mass", "singular", "exact orbits need a positive definite mass (no massless DOFs)");
  return mass_factor.solve(Eigen::MatrixXd::Identity(n, n));
}

HeldDofs holdDofs(const Eigen::MatrixXd& mass_inverse, const std::vector<int>& dofs) {
  const int g = static_cast<int>(dofs.size()), n = static_cast<int>(mass_inverse.rows());
  HeldDofs held;
  held.projector = mass_inverse;
  held.multiplier = Eigen::MatrixXd::Zero(g, n);
  if (g == 0) return held;
  Eigen::MatrixXd select = Eigen::MatrixXd::Zero(g, n);
  for (int i = 0; i < g; ++i) select(i, dofs[i]) = 1.0;
  const Eigen::MatrixXd pm = select * mass_inverse;  // P M⁻¹
  held.multiplier = -(pm * select.transpose()).ldlt().solve(pm);
  held.projector = mass_inverse + mass_inverse * select.transpose() * held.multiplier;
  return held;
}

double fastestRate(const Eigen::MatrixXd& mass_inverse, const Eigen::MatrixXd& stiffness,
                   const Eigen::MatrixXd& damping, const std::vector<int>& harmonics, double omega) {
  double rate = std::max(std::sqrt((mass_inverse * stiffness).cwiseAbs().rowwise().sum().maxCoeff()),
                         (mass_inverse * damping).cwiseAbs().rowwise().sum().maxCoeff());
  for (int k : harmonics) rate = std::max(rate, k * omega);
  return std::max(rate, omega);
}

}  // namespace eqhb::orbits
