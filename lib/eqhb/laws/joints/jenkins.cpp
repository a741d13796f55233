#include "eqhb/laws/joints/jenkins.h"

#include <algorithm>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/laws/scale_free_copy.h"
#include "eqhb/laws/dissipation_deficit.h"

namespace eqhb {

Jenkins::Jenkins(int dimension, double mu_n, double k_t, FrictionForm form, RhoSetting rho)
    : dimension_(dimension), mu_n_(mu_n), compliance_(1.0 / k_t), form_(form), rho_setting_(rho), rho_(rho.value) {
  if (dimension != 1 && dimension != 2)
    throwInputError("dofs", std::to_string(dimension) + " DOF(s)", "a jenkins law acts on 1 or 2 DOFs");
  if (!(mu_n >= 0.0) || !std::isfinite(mu_n))
    throwInputError("muN", formatNumber(mu_n), "friction limit must be finite and >= 0");
  if (!(k_t > 0.0) || !std::isfinite(k_t))
    throwInputError("k_t", formatNumber(k_t), "tangential stiffness must be finite and > 0");
  if (!(rho_ > 0.0) || !std::isfinite(rho_)) throwInputError(rho.field(), formatNumber(rho_), "must be finite and > 0");
  if (form == FrictionForm::kMinMax && dimension != 1)
    throwInputError("form", "\"minmax\"", "the minmax form is one-dimensional; use max or projection");
}

void Jenkins::evaluate(LawSamples& s, bool with_derivatives) const {
  const int m = dimension_;
  const Eigen::Index n = s.psi.rows();
  FrictionPoint point;
  double u[2], r[2];
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int b = 0; b < m; ++b) {
      r[b] = s.force(i, b);
      u[b] = s.velocity(i, b) + compliance_ * s.force_rate(i, b);
    }
    evaluateFriction(form_, m, rho_, u, r, mu_n_, point);
    for (int a = 0; a < m; ++a) s.psi(i, a) = point.psi[a];
    if (!with_derivatives) continue;
    for (int c = 0; c < m * m; ++c) {
      s.dpsi_dvelocity(i, c) = point.d_u[c];
      s.dpsi_dforce(i, c) = point.d_r[c];
      s.dpsi_dforce_rate(i, c) = compliance_ * point.d_u[c];
    }
  }
}

LocalVector Jenkins::solveStep(const StepProblem& step) const {
  const int m = dimension_;
  const LocalMatrix a =
      step.h * step.theta * step.delassus + compliance_ * LocalMatrix::Identity(m, m);
  const LocalVector r_start = step.force_start.size() == m ? step.force_start : LocalVector::Zero(m);
  // x_pred − w_start, with x_pred the end position at zero force.
  const LocalVector b = step.h * (step.theta * step.u_free + (1.0 - step.theta) * step.v_start) -
                        compliance_ * r_start;
  return minimiseOnDisc(a, b, mu_n_);
}

std::vector<std::pair<std::string, double>> Jenkins::violations(const LawSamples& s,
                                                                const PhysicalScales& scales) const {
  const int m = dimension_;
  const Eigen::Index n = s.force.rows();
  auto slip = [&](Eigen::Index i) {
    Eigen::Vector2d u = Eigen::Vector2d::Zero();
    for (int b = 0; b < m; ++b) u[b] = s.velocity(i, b) + compliance_ * s.force_rate(i, b);
    return u;
  };
  double u_scale = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) u_scale = std::max(u_scale, slip(i).norm());
  u_scale = invariantScale(u_scale, scales.velocity);  // stuck: u ≡ 0 up to rounding
  if (mu_n_ <= 0.0) return {{"force_limit_excess", 0.0}, {"sliding_force_error", 0.0}, {"dissipation_deficit", 0.0}};
  double excess = 0.0, sliding = 0.0;
  DissipationDeficit deficit;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Vector2d r = Eigen::Vector2d::Zero();
    for (int b = 0; b < m; ++b) r[b] = s.force(i, b);
    excess = std::max(excess, r.norm() / mu_n_ - 1.0);
    const Eigen::Vector2d u = slip(i);
    if (u.norm() > kElasticSlidingFraction * u_scale) sliding = std::max(sliding, (r + mu_n_ * u / u.norm()).norm() / mu_n_);
    deficit.add(r.dot(u), mu_n_ * u.norm());
  }
  const double floor = kElasticSlidingFraction * static_cast<double>(n) * mu_n_ * u_scale;
  return {{"force_limit_excess", excess},
          {"sliding_force_error", sliding},
          {"dissipation_deficit", deficit.value(floor)}};
}

std::optional<Law::RhoComparison> Jenkins::compareRho(const LawScales& scales) const {
  return RhoComparison{rho_, scaleFreeFrictionRho(form_, scales.omega * (scales.compliance + compliance_))};
}

std::shared_ptr<Law> Jenkins::withScaleFreeRho(const LawScales& scales) const {
  return copyWithScaleFreeRho(*this, rho_setting_, &Jenkins::rho_, scales);
}

double Jenkins::residualScale(const PhysicalScales& s, int) const {
  return frictionResidualScale(form_, rho_, s);  // the slip velocity u in the velocity scale
}

std::optional<StaticStatus> Jenkins::staticStatus(const LawSamples& rest) const {
  return frictionStatus(rest.force.row(0).norm(), mu_n_);
}

}  // namespace eqhb
