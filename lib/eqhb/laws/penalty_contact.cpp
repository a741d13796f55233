#include "eqhb/laws/penalty_contact.h"
#include "eqhb/laws/contact_status.h"

#include <algorithm>

#include "eqhb/error.h"

namespace eqhb {

PenaltyContact::PenaltyContact(double stiffness, double gap) : stiffness_(stiffness), gap_(gap) {
  if (!(stiffness > 0.0) || !std::isfinite(stiffness))
    throwInputError("stiffness", formatNumber(stiffness), "must be finite and > 0");
  if (!std::isfinite(gap)) throwInputError("gap", formatNumber(gap), "must be finite (no NaN or Inf)");
}

void PenaltyContact::evaluate(LawSamples& s, bool with_derivatives) const {
  const Eigen::Index n = s.psi.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double penetration = s.displacement(i, 0) - gap_;  // −g
    const bool pressed = penetration > 0.0;
    s.psi(i, 0) = s.force(i, 0) - (pressed ? stiffness_ * penetration : 0.0);
    if (with_derivatives) {
      s.dpsi_ddisplacement(i, 0) = pressed ? -stiffness_ : 0.0;
      s.dpsi_dforce(i, 0) = 1.0;
    }
  }
}

LocalVector PenaltyContact::solveStep(const StepProblem& step) const {
  // x_θ = x_start + θ h (θ u_end + (1 − θ) v_start), u_end = u_free + D p
  // (D < 0: the force on the structure is −p), as for the cubic spring.
  const double th = step.theta * step.h;
  const double base = step.x_start[0] + th * (step.theta * step.u_free[0] + (1.0 - step.theta) * step.v_start[0]);
  const double slope = th * step.theta * step.delassus(0, 0);  // ∂x_θ/∂p <= 0
  // p = k max(0, r + slope p), r = base − g0: p = 0 when r <= 0, else the
  // linear branch k r / (1 − k slope) > 0, which is then in contact.
  const double r = base - gap_;
  LocalVector pressure(1);
  pressure[0] = r > 0.0 ? stiffness_ * r / (1.0 - stiffness_ * slope) : 0.0;
  return pressure;
}

std::vector<std::pair<std::string, double>> PenaltyContact::violations(const LawSamples& s,
                                                                       const PhysicalScales& scales) const {
  const Eigen::ArrayXd penetration = s.displacement.col(0).array() - gap_;
  const Eigen::ArrayXd p = s.force.col(0).array();
  const Eigen::ArrayXd law = p - stiffness_ * penetration.max(0.0);
  const double scale = std::max(invariantScale(p.abs().maxCoeff(), scales.force), 1e-300);
  return {{"penalty_law", law.abs().maxCoeff() / scale}, {"negative_pressure", std::max(0.0, -p.minCoeff()) / scale}};
}

std::optional<StaticStatus> PenaltyContact::staticStatus(const LawSamples& rest) const {
  return normalContactStatus(gap_, rest);
}

}  // namespace eqhb
