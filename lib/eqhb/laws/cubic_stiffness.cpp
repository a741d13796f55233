#include "eqhb/laws/cubic_stiffness.h"

#include <cmath>

#include "eqhb/error.h"

namespace eqhb {

CubicStiffness::CubicStiffness(double epsilon) : epsilon_(epsilon) {
  if (!std::isfinite(epsilon)) throwInputError("epsilon", formatNumber(epsilon), "must be finite");
}

void CubicStiffness::evaluate(LawSamples& s, bool with_derivatives) const {
  const Eigen::Index n = s.psi.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = s.displacement(i, 0);
    s.psi(i, 0) = s.force(i, 0) + epsilon_ * x * x * x;
    if (with_derivatives) {
      s.dpsi_ddisplacement(i, 0) = 3.0 * epsilon_ * x * x;
      s.dpsi_dforce(i, 0) = 1.0;
    }
  }
}

LocalVector CubicStiffness::solveStep(const StepProblem& step) const {
  // x_θ = x_start + θ h (θ u_end + (1 − θ) v_start), u_end = u_free + D λ.
  const double th = step.theta * step.h;
  const double base = step.x_start[0] + th * (step.theta * step.u_free[0] + (1.0 - step.theta) * step.v_start[0]);
  const double slope = th * step.theta * step.delassus(0, 0);
  double lambda = -epsilon_ * base * base * base;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double x = base + slope * lambda;
    const double phi = lambda + epsilon_ * x * x * x;
    const double dphi = 1.0 + 3.0 * epsilon_ * x * x * slope;
    const double next = lambda - phi / dphi;
    const bool done = std::abs(next - lambda) <= 1e-15 * (1.0 + std::abs(lambda));
    lambda = next;
    if (done) break;
  }
  LocalVector force(1);
  force[0] = lambda;
  return force;
}

std::vector<std::pair<std::string, double>> CubicStiffness::violations(const LawSamples& s,
                                                                       const PhysicalScales& scales) const {
  const Eigen::ArrayXd x = s.displacement.col(0).array();
  const Eigen::ArrayXd residual = s.force.col(0).array() + epsilon_ * x * x * x;
  const double scale = std::max(invariantScale(s.force.col(0).cwiseAbs().maxCoeff(), scales.force), 1e-300);
  return {{"dae_residual", residual.abs().maxCoeff() / scale}};
}

}  // namespace eqhb
