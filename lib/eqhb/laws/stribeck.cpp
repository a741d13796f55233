#include "eqhb/laws/stribeck.h"

#include <algorithm>
#include <cmath>

#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/error.h"
#include "eqhb/laws/scale_free_copy.h"
#include "eqhb/laws/joints/friction_kernels.h"

namespace eqhb {

Stribeck::Stribeck(double mu_n_dynamic, double mu_n_static, double v_s, RhoSetting rho)
    : dynamic_(mu_n_dynamic), drop_(mu_n_static - mu_n_dynamic), v_s_(v_s), rho_setting_(rho), rho_(rho.value) {
  if (!(mu_n_dynamic >= 0.0) || !std::isfinite(mu_n_dynamic))
    throwInputError("muN_dynamic", formatNumber(mu_n_dynamic), "friction limit must be finite and >= 0");
  if (!(mu_n_static >= mu_n_dynamic) || !std::isfinite(mu_n_static))
    throwInputError("muN_static", formatNumber(mu_n_static), "must be finite and >= muN_dynamic");
  if (!(v_s > 0.0) || !std::isfinite(v_s)) throwInputError("v_s", formatNumber(v_s), "must be finite and > 0");
  if (!(rho_ > 0.0) || !std::isfinite(rho_)) throwInputError(rho.field(), formatNumber(rho_), "must be finite and > 0");
}

double Stribeck::limit(double v) const { return dynamic_ + drop_ * std::exp(-std::abs(v) / v_s_); }

void Stribeck::evaluate(LawSamples& s, bool with_derivatives) const {
  const Eigen::Index n = s.psi.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double v = s.velocity(i, 0), r = s.force(i, 0);
    const double decay = drop_ * std::exp(-std::abs(v) / v_s_);
    const double l = dynamic_ + decay;
    const double dl = v > 0.0 ? -decay / v_s_ : v < 0.0 ? decay / v_s_ : 0.0;  // L'(v)
    const MinMaxBranch branch = minMaxBranch(rho_, v, r, l);
    s.psi(i, 0) = branch.psi;
    if (with_derivatives) {
      const double lower = branch.lower ? 1.0 : 0.0, upper = branch.upper ? 1.0 : 0.0;
      s.dpsi_dvelocity(i, 0) = 1.0 + lower * (rho_ * dl - 1.0) + upper * (-rho_ * dl - 1.0);
      s.dpsi_dforce(i, 0) = rho_ * (lower + upper);
    }
  }
}

LocalVector Stribeck::solveStep(const StepProblem& step) const {
  LocalVector force(1);
  const double d = step.delassus(0, 0), u_free = step.u_free[0];
  // A reversal inside the step holds the mean force; the speed there is
  // O(h), so the limit on both sides is L(0) up to O(h) (O(h²) in the impulse).
  force[0] = reversingStepForce(step.v_start[0], u_free, d, limit(0.0),
                                stickOrSlideForce(u_free, step.v_start[0], d, step.theta));
  return force;
}

double Stribeck::stickOrSlideForce(double u_free, double v_start, double d, double theta) const {
  if (std::abs(u_free) <= d * limit(0.0)) return -u_free / d;  // sticks: u_end = 0
  // Slides the way of u_free with u_end = s w: the limit is taken at the
  // step's θ-velocity v_θ = θ u_end + (1 − θ) v_start, as the structure's
  // forces are (at u_end alone the step would be first order for θ = ½).
  // φ(w) = w − |u_free| + D L(v_θ(w)): φ(0) < 0 <= φ(|u_free|), as L(v) <= L(0).
  const double s = u_free > 0.0 ? 1.0 : -1.0;
  auto velocity = [&](double w) { return theta * s * w + (1.0 - theta) * v_start; };
  double low = 0.0, high = std::abs(u_free), w = high;
  for (int iteration = 0; iteration < 200 && high - low > 1e-15 * std::abs(u_free); ++iteration) {
    const double v_theta = velocity(w), speed = std::abs(v_theta);
    const double phi = w - std::abs(u_free) + d * limit(speed);
    if (phi > 0.0) high = w;
    else low = w;
    // dv_θ/dw = θ s sign(v_θ); L'(v) = −drop e^{−|v|/v_s} sign(v) / v_s.
    const double dphi = 1.0 - d * theta * s * (v_theta >= 0.0 ? 1.0 : -1.0) * drop_ * std::exp(-speed / v_s_) / v_s_;
    const double newton = dphi > 0.0 ? w - phi / dphi : -1.0;
    w = newton > low && newton < high ? newton : 0.5 * (low + high);
  }
  return -s * limit(std::abs(velocity(w)));
}

std::vector<std::pair<std::string, double>> Stribeck::violations(const LawSamples& s,
                                                                 const PhysicalScales& scales) const {
  Eigen::VectorXd limits(s.velocity.rows());
  for (Eigen::Index i = 0; i < limits.size(); ++i) limits[i] = limit(s.velocity(i, 0));
  return frictionViolations(s.velocity.col(0), s.force.col(0), limits, scales.velocity);
}

std::optional<Law::RhoComparison> Stribeck::compareRho(const LawScales& scales) const {
  return RhoComparison{rho_, kScaleFreeRhoWeight * scales.mobility()};
}

std::shared_ptr<Law> Stribeck::withScaleFreeRho(const LawScales& scales) const {
  return copyWithScaleFreeRho(*this, rho_setting_, &Stribeck::rho_, scales);
}

double Stribeck::residualScale(const PhysicalScales& s, int) const {
  return std::min(s.velocity, rho_ * s.force);  // v and ρ r, as Coulomb's min/max form
}

}  // namespace eqhb
