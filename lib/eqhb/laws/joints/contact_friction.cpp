#include "eqhb/laws/joints/contact_friction.h"

#include <algorithm>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/laws/form_names.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/dissipation_deficit.h"

namespace eqhb {

namespace {
constexpr FormName<NormalForm> kNormalFormNames[] = {
    {NormalForm::kMin, "min"}, {NormalForm::kFischerBurmeister, "fischer-burmeister"},
    {NormalForm::kCompliant, "compliant"}};
}  // namespace

NormalForm parseNormalForm(const std::string& name, const std::string& field) {
  return parseForm(kNormalFormNames, name, field);
}

std::string normalFormName(NormalForm form) { return formName(kNormalFormNames, form); }

ContactFriction::ContactFriction(const ContactFrictionParameters& p)
    : p_(p), normal_rho_(p.rho.value), friction_rho_(p.rho.value) {
  if (p.tangential != 1 && p.tangential != 2)
    throwInputError("dofs", std::to_string(p.tangential + 1) + " DOF(s)",
                    "a contact-friction law acts on one normal and 1 or 2 tangential DOFs");
  if (!(p.mu >= 0.0) || !std::isfinite(p.mu)) throwInputError("mu", formatNumber(p.mu), "friction coefficient must be finite and >= 0");
  if (!(p.preload >= 0.0) || !std::isfinite(p.preload))
    throwInputError("preload", formatNumber(p.preload), "normal preload N0 must be finite and >= 0");
  if (!std::isfinite(p.gap)) throwInputError("gap", formatNumber(p.gap), "must be finite (no NaN or Inf)");
  if (!(p.rho.value > 0.0) || !std::isfinite(p.rho.value))
    throwInputError(p.rho.field(), formatNumber(p.rho.value), "must be finite and > 0");
  if (p.normal == NormalForm::kCompliant) {
    if (!p.normal_stiffness) throwInputError("k_n", "(missing)", "the compliant normal form needs a contact stiffness k_n > 0");
    if (!(*p.normal_stiffness > 0.0) || !std::isfinite(*p.normal_stiffness))
      throwInputError("k_n", formatNumber(*p.normal_stiffness), "contact stiffness must be finite and > 0");
  } else if (p.normal_stiffness) {
    throwInputError("k_n", formatNumber(*p.normal_stiffness),
                    "a contact stiffness is only used by form = \"compliant\" (this law has form = \"" +
                        normalFormName(p.normal) + "\")");
  }
  if (p.tangential_stiffness) {
    if (!(*p.tangential_stiffness > 0.0) || !std::isfinite(*p.tangential_stiffness))
      throwInputError("k_t", formatNumber(*p.tangential_stiffness), "tangential stiffness must be finite and > 0");
    compliance_ = 1.0 / *p.tangential_stiffness;
  }
  if (p.friction == FrictionForm::kMinMax && p.tangential != 1)
    throwInputError("friction_form", "\"minmax\"", "the minmax form has one tangential DOF; use max or projection");
}

void ContactFriction::evaluate(LawSamples& s, bool with_derivatives) const {
  const int m = p_.tangential, d = 1 + m;
  const Eigen::Index n = s.psi.rows();
  FrictionPoint point;
  double u[2], r[2];
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x_n = s.displacement(i, 0);
    const double pressure = p_.preload - s.force(i, 0);  // ∂p/∂λ_n = −1
    double psi = 0.0, d_x = 0.0, d_p = 0.0;
    switch (p_.normal) {
      case NormalForm::kMin: {
        const double a = normal_rho_ * (p_.gap - x_n);
        if (a < pressure) psi = a, d_x = -normal_rho_;
        else psi = pressure, d_p = 1.0;
        break;
      }
      case NormalForm::kFischerBurmeister: {
        const double a = normal_rho_ * (p_.gap - x_n);
        const double root = std::hypot(a, pressure);
        psi = a + pressure - root;
        const double da = root > 0.0 ? 1.0 - a / root : 1.0 - std::sqrt(0.5);
        d_p = root > 0.0 ? 1.0 - pressure / root : 1.0 - std::sqrt(0.5);
        d_x = -normal_rho_ * da;
        break;
      }
      case NormalForm::kCompliant: {
        // p = k_n max(0, −g) is the complementarity 0 <= p ⊥ g + p/k_n >= 0:
        // the min form on the gap of the layer's far side.
        const double a = normal_rho_ * (p_.gap - x_n + pressure / *p_.normal_stiffness);
        if (a < pressure) psi = a, d_x = -normal_rho_, d_p = normal_rho_ / *p_.normal_stiffness;
        else psi = pressure, d_p = 1.0;
        break;
      }
    }
    s.psi(i, 0) = psi;
    for (int b = 0; b < m; ++b) {
      r[b] = s.force(i, 1 + b);
      u[b] = s.velocity(i, 1 + b) + (compliance_ > 0.0 ? compliance_ * s.force_rate(i, 1 + b) : 0.0);
    }
    const double limit = p_.mu * std::max(pressure, 0.0);
    evaluateFriction(p_.friction, m, friction_rho_, u, r, limit, point);
    for (int a = 0; a < m; ++a) s.psi(i, 1 + a) = point.psi[a];
    if (!with_derivatives) continue;
    for (int c = 0; c < d * d; ++c) {
      s.dpsi_ddisplacement(i, c) = 0.0;
      s.dpsi_dvelocity(i, c) = 0.0;
      s.dpsi_dforce(i, c) = 0.0;
      s.dpsi_dforce_rate(i, c) = 0.0;
    }
    s.dpsi_ddisplacement(i, 0) = d_x;
    s.dpsi_dforce(i, 0) = -d_p;
    const double dlimit_dlambda = pressure > 0.0 ? -p_.mu : 0.0;
    for (int a = 0; a < m; ++a) {
      const int row = (1 + a) * d;
      s.dpsi_dforce(i, row) = point.d_limit[a] * dlimit_dlambda;
      for (int b = 0; b < m; ++b) {
        s.dpsi_dvelocity(i, row + 1 + b) = point.d_u[a * m + b];
        s.dpsi_dforce(i, row + 1 + b) = point.d_r[a * m + b];
        s.dpsi_dforce_rate(i, row + 1 + b) = compliance_ * point.d_u[a * m + b];
      }
    }
  }
}

LocalVector ContactFriction::solveStep(const StepProblem& step) const {
  const int m = p_.tangential;
  const double h = step.h, theta = step.theta;
  const double d_nn = step.delassus(0, 0);
  LocalVector lambda = step.force_start.size() == 1 + m ? step.force_start : LocalVector::Zero(1 + m);
  // Tangential blocks, copied element by element (small fixed-capacity storage).
  LocalVector r_t(m), b(m), r_start(m), free_t(m), v_t(m), d_tn(m);
  LocalMatrix a(m, m);
  for (int i = 0; i < m; ++i) {
    r_t[i] = lambda[1 + i];
    r_start[i] = lambda[1 + i];
    free_t[i] = step.u_free[1 + i];
    v_t[i] = step.v_start[1 + i];
    d_tn[i] = step.delassus(1 + i, 0);
    for (int j = 0; j < m; ++j)
      a(i, j) = (compliance_ > 0.0 ? h * theta : 1.0) * step.delassus(1 + i, 1 + j) + (i == j ? compliance_ : 0.0);
  }
  for (int iteration = 0; iteration < 500; ++iteration) {
    // Normal, given r_t: end velocity u_n = c − D_nn p.
    double c = step.u_free[0] + d_nn * p_.preload;
    for (int j = 0; j < m; ++j) c += step.delassus(0, 1 + j) * r_t[j];
    double pressure = 0.0;
    if (p_.normal == NormalForm::kCompliant) {
      const double q = step.x_start[0] + h * (1.0 - theta) * step.v_start[0] + h * theta * c - p_.gap;
      const double k_n = *p_.normal_stiffness;
      pressure = q > 0.0 ? k_n * q / (1.0 + k_n * h * theta * d_nn) : 0.0;
    } else {
      const double gap = p_.gap - step.x_start[0], gap_rate = -step.v_start[0];
      if (gap + 0.5 * h * gap_rate <= 0.0)  // closed at mid-step: 0 <= ġ_end + e ġ_start ⊥ p >= 0
        pressure = std::max(0.0, (c + step.restitution * step.v_start[0]) / d_nn);
    }
    const double lambda_n = p_.preload - pressure;
    // Tangential, given p: maximal dissipation on the disc of radius μp,
    // for the slip velocity (rigid) or the slider displacement (k_t).
    if (compliance_ > 0.0)
      b = h * (theta * (free_t + d_tn * lambda_n) + (1.0 - theta) * v_t) - compliance_ * r_start;
    else
      b = free_t + d_tn * lambda_n;
    r_t = minimiseOnDisc(a, b, p_.mu * pressure);
    double change = std::abs(lambda_n - lambda[0]), size = std::max(1.0, std::abs(lambda_n));
    lambda[0] = lambda_n;
    for (int j = 0; j < m; ++j) {
      change = std::max(change, std::abs(r_t[j] - lambda[1 + j]));
      size = std::max(size, std::abs(r_t[j]));
      lambda[1 + j] = r_t[j];
    }
    if (change <= 1e-14 * size) break;
  }
  return lambda;
}

std::vector<std::pair<std::string, double>> ContactFriction::violations(const LawSamples& s,
                                                                        const PhysicalScales& scales) const {
  const int m = p_.tangential;
  const Eigen::Index n = s.force.rows();
  double p_max = 0.0, p_min = 0.0, g_scale = 0.0, g_min = 0.0, u_scale = 0.0;
  auto slip = [&](Eigen::Index i) {
    Eigen::Vector2d u = Eigen::Vector2d::Zero();
    for (int b = 0; b < m; ++b) u[b] = s.velocity(i, 1 + b) + compliance_ * s.force_rate(i, 1 + b);
    return u;
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    const double p = p_.preload - s.force(i, 0), g = p_.gap - s.displacement(i, 0);
    p_max = std::max(p_max, p);
    p_min = std::min(p_min, p);
    g_min = std::min(g_min, g);
    g_scale = std::max(g_scale, std::abs(g));
    for (int b = 0; b < m; ++b) g_scale = std::max(g_scale, std::abs(s.displacement(i, 1 + b)));
    u_scale = std::max(u_scale, slip(i).norm());
  }
  // Never against less than a fraction of the problem's scales: an open or
  // stuck contact has p or u ≡ 0 up to rounding.
  p_max = invariantScale(p_max, scales.force);
  g_scale = invariantScale(g_scale, scales.displacement);
  u_scale = invariantScale(u_scale, scales.velocity);
  auto relative = [](double value, double scale) { return scale > 0.0 ? value / scale : 0.0; };
  const double limit_scale = p_.mu * p_max;
  // An elastic slider's slip velocity jumps where stick ends (see kElasticSlidingFraction).
  const double sliding_fraction = compliance_ > 0.0 ? kElasticSlidingFraction : kSlidingFraction;
  double complementarity = 0.0, compliance = 0.0, excess = 0.0, sliding = 0.0;
  DissipationDeficit deficit;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double p = p_.preload - s.force(i, 0), g = p_.gap - s.displacement(i, 0);
    complementarity = std::max(complementarity, std::abs(g * p));
    if (p_.normal_stiffness)
      compliance = std::max(compliance, std::abs(p - *p_.normal_stiffness * std::max(0.0, -g)));
    Eigen::Vector2d r = Eigen::Vector2d::Zero();
    for (int b = 0; b < m; ++b) r[b] = s.force(i, 1 + b);
    const double limit = p_.mu * std::max(p, 0.0);
    excess = std::max(excess, r.norm() - limit);
    const Eigen::Vector2d u = slip(i);
    if (u.norm() > sliding_fraction * u_scale && p > 0.05 * p_max)  // clearly sliding and pressed: r = −μp u/‖u‖
      sliding = std::max(sliding, (r + limit * u / u.norm()).norm());
    deficit.add(r.dot(u), limit * u.norm());
  }
  std::vector<std::pair<std::string, double>> out = {{"negative_pressure", relative(-p_min, p_max)}};
  if (p_.normal == NormalForm::kCompliant) {
    out.push_back({"compliance_error", relative(compliance, p_max)});
  } else {
    out.push_back({"penetration", relative(-g_min, g_scale)});
    out.push_back({"complementarity", relative(complementarity, g_scale * p_max)});
  }
  out.push_back({"force_limit_excess", relative(excess, limit_scale)});
  out.push_back({"sliding_force_error", relative(sliding, limit_scale)});
  out.push_back({"dissipation_deficit", deficit.value(sliding_fraction * static_cast<double>(n) * limit_scale * u_scale)});
  return out;
}

double ContactFriction::forceLevel() const { return p_.preload * std::max(1.0, p_.mu); }

double ContactFriction::displacementLevel() const { return std::abs(p_.gap); }

double ContactFriction::residualScale(const PhysicalScales& s, int component) const {
  if (component == 0) return std::min(normal_rho_ * s.displacement, s.force);  // ρ g (+ p/k_n) and p
  return frictionResidualScale(p_.friction, friction_rho_, s);
}

std::optional<Law::RhoComparison> ContactFriction::compareRho(const LawScales& scales) const {
  const double layer = p_.normal == NormalForm::kCompliant ? 1.0 / *p_.normal_stiffness : 0.0;
  return RhoComparison{normal_rho_, kScaleFreeRhoWeight / (scales.compliance + layer)};
}

std::shared_ptr<Law> ContactFriction::withScaleFreeRho(const LawScales& scales) const {
  if (!p_.rho.scale_free) return nullptr;
  auto copy = std::make_shared<ContactFriction>(*this);
  copy->normal_rho_ = p_.rho.factor * compareRho(scales)->scale_free;
  copy->friction_rho_ = p_.rho.factor * scaleFreeFrictionRho(p_.friction, scales.omega * (scales.compliance + compliance_));
  return copy;
}

std::optional<StaticStatus> ContactFriction::staticStatus(const LawSamples& rest) const {
  const double pressure = p_.preload - rest.force(0, 0);  // λ_n = N0 − p
  StaticStatus s = frictionStatus(rest.force.row(0).tail(p_.tangential).norm(), p_.mu * std::max(pressure, 0.0));
  if (!(pressure > 0.0)) s.state = StaticStatus::State::kOpen;
  s.gap = p_.gap - rest.displacement(0, 0);
  s.normal_force = pressure;
  return s;
}

}  // namespace eqhb
