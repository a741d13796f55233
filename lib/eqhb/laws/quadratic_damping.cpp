#include "eqhb/laws/quadratic_damping.h"

#include <cmath>

#include "eqhb/error.h"

namespace eqhb {

QuadraticDamping::QuadraticDamping(double coefficient) : coefficient_(coefficient) {
  if (!std::isfinite(coefficient) || coefficient < 0.0)
    throwInputError("coefficient", formatNumber(coefficient), "must be finite and >= 0 (a damper dissipates)");
}

void QuadraticDamping::evaluate(LawSamples& s, bool with_derivatives) const {
  const Eigen::Index n = s.psi.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double v = s.velocity(i, 0);
    s.psi(i, 0) = s.force(i, 0) + coefficient_ * v * std::abs(v);
    if (with_derivatives) {
      s.dpsi_dvelocity(i, 0) = 2.0 * coefficient_ * std::abs(v);
      s.dpsi_dforce(i, 0) = 1.0;
    }
  }
}

LocalVector QuadraticDamping::solveStep(const StepProblem& step) const {
  // u = b + D λ and λ = −c u|u| give c D u|u| + u − b = 0, whose root has
  // the sign of b: |u| = 2|b| / (1 + sqrt(1 + 4 c D |b|)) (the stable form
  // of the quadratic's root, exact also for c D = 0).
  const double b = step.u_free[0], d = step.delassus(0, 0);
  const double u = 2.0 * b / (1.0 + std::sqrt(1.0 + 4.0 * coefficient_ * d * std::abs(b)));
  LocalVector force(1);
  force[0] = -coefficient_ * u * std::abs(u);
  return force;
}

std::vector<std::pair<std::string, double>> QuadraticDamping::violations(const LawSamples& s,
                                                                         const PhysicalScales& scales) const {
  const Eigen::ArrayXd v = s.velocity.col(0).array();
  const Eigen::ArrayXd residual = s.force.col(0).array() + coefficient_ * v * v.abs();
  const double scale = std::max(invariantScale(s.force.col(0).cwiseAbs().maxCoeff(), scales.force), 1e-300);
  return {{"dae_residual", residual.abs().maxCoeff() / scale}};
}

}  // namespace eqhb
