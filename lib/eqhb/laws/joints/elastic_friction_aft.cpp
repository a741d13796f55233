#include "eqhb/laws/joints/elastic_friction_aft.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "eqhb/error.h"
#include "eqhb/laws/contact_status.h"
#include "eqhb/laws/joints/jenkins.h"

namespace eqhb {

namespace {

// The parameters checked (InputError naming the field), returned as given.
const ElasticFrictionParameters& checked(const ElasticFrictionParameters& p) {
  if (p.tangents != 1 && p.tangents != 2)
    throwInputError("tangents", std::to_string(p.tangents), "an elastic-friction element has 1 or 2 tangents");
  if (!(p.k_t > 0.0) || !std::isfinite(p.k_t))
    throwInputError("k_t", formatNumber(p.k_t), "tangential stiffness must be finite and > 0");
  if (p.constant_limit) {
    if (!(*p.constant_limit >= 0.0) || !std::isfinite(*p.constant_limit))
      throwInputError("muN", formatNumber(*p.constant_limit), "friction limit must be finite and >= 0");
    return p;
  }
  if (!(p.mu >= 0.0) || !std::isfinite(p.mu))
    throwInputError("mu", formatNumber(p.mu), "friction coefficient must be finite and >= 0");
  if (!(p.k_n > 0.0) || !std::isfinite(p.k_n))
    throwInputError("k_n", formatNumber(p.k_n), "normal stiffness must be finite and > 0");
  if (!std::isfinite(p.gap)) throwInputError("gap", formatNumber(p.gap), "must be finite (no NaN or Inf)");
  return p;
}

// The same element as contact-friction (the header): a compliant normal
// without preload, the slider behind k_t.
ContactFrictionParameters asContactFriction(const ElasticFrictionParameters& p) {
  ContactFrictionParameters c;
  c.tangential = p.tangents;
  c.mu = p.mu;
  c.gap = p.gap;
  c.normal = NormalForm::kCompliant;
  c.normal_stiffness = p.k_n;
  c.tangential_stiffness = p.k_t;
  return c;
}

}  // namespace

ElasticFrictionAft::ElasticFrictionAft(const ElasticFrictionParameters& parameters)
    : p_(checked(parameters)) {
  if (!onPlane()) step_law_.emplace(asContactFriction(p_));
}

double ElasticFrictionAft::displacementLevel() const { return onPlane() ? 0.0 : std::abs(p_.gap); }

namespace {

constexpr int kMaxTangents = 2;

// One sample's return map (the header): T and, on a slip, w move. `e` the
// trial's direction and `ratio` = μp/‖T*‖ (0 when open) serve the Jacobian.
struct ReturnMap {
  double pressure = 0.0;
  bool pressed = false, slipped = false;
  double ratio = 0.0;
  double e[kMaxTangents] = {0.0, 0.0};
  double force[kMaxTangents] = {0.0, 0.0};
};

// `u_n` is not read on a plane (constant limit).
ReturnMap returnMap(const ElasticFrictionParameters& p, double u_n, const double* u_t, double* w) {
  ReturnMap r;
  double limit = 0.0;
  if (p.constant_limit) {
    limit = *p.constant_limit;
  } else {
    const double penetration = u_n - p.gap;
    r.pressed = penetration > 0.0;
    r.pressure = r.pressed ? p.k_n * penetration : 0.0;
    limit = p.mu * r.pressure;
  }
  double norm2 = 0.0;
  for (int a = 0; a < p.tangents; ++a) {
    r.force[a] = p.k_t * (u_t[a] - w[a]);
    norm2 += r.force[a] * r.force[a];
  }
  const double norm = std::sqrt(norm2);
  r.slipped = norm > limit;
  if (!r.slipped) return r;
  r.ratio = limit / norm;
  for (int a = 0; a < p.tangents; ++a) {
    r.e[a] = r.force[a] / norm;
    r.force[a] = limit * r.e[a];
    w[a] = u_t[a] - r.force[a] / p.k_t;
  }
  return r;
}

// The history weights of tangent α (law component t0 + α) at sample i, for
// input component b at sample k: σ k_t ∂w_α(t_i)/∂u_b(t_k) (σ = −1 on a
// plane, where Ψ = λ + T), laid out as LawSamples says (ab K + k with K = N
// samples).
inline double& sensitivity(LawSamples& s, int t0, int d, int n, int i, int alpha, int b, int k) {
  return s.history_weight(i, ((t0 + alpha) * d + b) * n + k);
}

}  // namespace

void ElasticFrictionAft::evaluate(LawSamples& s, bool with_derivatives) const {
  const int n = static_cast<int>(s.psi.rows()), d = dimension(), m = p_.tangents, t0 = firstTangent();
  // Ψ_t = λ_t − σ T: σ = 1 (λ the force on the contact), −1 on a plane (λ = −T).
  const double sigma = onPlane() ? -1.0 : 1.0, k_t = sigma * p_.k_t;
  if (with_derivatives && s.history_weight.cols() != d * d * historyTermsOn(n))
    throw std::logic_error("ElasticFrictionAft: samples sized without history terms (LawSamples::resize)");
  // The start: ū_t or the static anchor (no dependence on u).
  double w[kMaxTangents] = {0.0, 0.0};
  double reach = 0.0;  // the size of u_t and of the slider's play, for the periodicity test
  for (int a = 0; a < m; ++a) {
    w[a] = anchor_.empty() ? s.displacement.col(t0 + a).mean() : anchor_[a];
    reach = std::max(reach, s.displacement.col(t0 + a).cwiseAbs().maxCoeff());
  }
  reach += (onPlane() ? *p_.constant_limit
                      : p_.mu * p_.k_n * std::max(0.0, s.displacement.col(0).maxCoeff() - p_.gap)) /
           p_.k_t;
  if (with_derivatives) {
    s.dpsi_ddisplacement.setZero();
    s.dpsi_dforce.setZero();
    for (int c = 0; c < s.history_sample.cols(); ++c) s.history_sample.col(c).setConstant(c % n);
    s.history_weight.setZero();
    if (anchor_.empty())  // ∂ū_t/∂u_t(t_k) = 1/N, written where pass 1 reads its start
      for (int alpha = 0; alpha < m; ++alpha)
        for (int k = 0; k < n; ++k) sensitivity(s, t0, d, n, 0, alpha, t0 + alpha, k) = k_t / n;
  }
  double u_t[kMaxTangents];
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const double begin[kMaxTangents] = {w[0], w[1]};
    for (int i = 0; i < n; ++i) {
      for (int a = 0; a < m; ++a) u_t[a] = s.displacement(i, t0 + a);
      const ReturnMap r = returnMap(p_, s.displacement(i, 0), u_t, w);
      if (!onPlane()) s.psi(i, 0) = s.force(i, 0) - r.pressure;
      for (int a = 0; a < m; ++a) s.psi(i, t0 + a) = s.force(i, t0 + a) - sigma * r.force[a];
      if (!with_derivatives) continue;
      for (int a = 0; a < d; ++a) s.dpsi_dforce(i, a * d + a) = 1.0;
      if (!onPlane()) s.dpsi_ddisplacement(i, 0) = r.pressed ? -p_.k_n : 0.0;
      for (int a = t0; a < d; ++a) s.dpsi_ddisplacement(i, a * d + a) = -k_t;
      // The slider's sensitivity from the previous sample (pass 1's first
      // sample: the start, already in row 0).
      const int previous = i > 0 ? i - 1 : pass == 0 ? 0 : n - 1;
      for (int b = 0; b < d; ++b)
        for (int k = 0; k < n; ++k) {
          double h[kMaxTangents] = {0.0, 0.0}, eh = 0.0;
          for (int alpha = 0; alpha < m; ++alpha) {
            h[alpha] = sensitivity(s, t0, d, n, previous, alpha, b, k);
            eh += r.e[alpha] * h[alpha];
          }
          // Stick: kept; slip: P h, P = ratio (I − e eᵀ).
          for (int alpha = 0; alpha < m; ++alpha)
            sensitivity(s, t0, d, n, i, alpha, b, k) = r.slipped ? r.ratio * (h[alpha] - r.e[alpha] * eh) : h[alpha];
        }
      if (!r.slipped) continue;
      // Slip: + k_t (I − P) ∂u_t(t_i) − μ e ∂p(t_i).
      for (int alpha = 0; alpha < m; ++alpha) {
        for (int beta = 0; beta < m; ++beta) {
          const double projector = r.ratio * ((alpha == beta ? 1.0 : 0.0) - r.e[alpha] * r.e[beta]);
          sensitivity(s, t0, d, n, i, alpha, t0 + beta, i) += k_t * ((alpha == beta ? 1.0 : 0.0) - projector);
        }
        if (r.pressed) sensitivity(s, t0, d, n, i, alpha, 0, i) -= sigma * p_.mu * r.e[alpha] * p_.k_n;
      }
    }
    double moved = 0.0;
    for (int a = 0; a < m; ++a) moved = std::max(moved, std::abs(w[a] - begin[a]));
    if (moved <= 1e-14 * reach) break;  // this pass started where it ended: periodic
  }
}

std::vector<std::pair<std::string, double>> ElasticFrictionAft::violations(const LawSamples& samples,
                                                                           const PhysicalScales& scales) const {
  LawSamples s = samples;  // not a hot path: the law is evaluated again on a copy
  evaluate(s, false);
  const int m = p_.tangents;
  const double scale = std::max(invariantScale(s.force.cwiseAbs().maxCoeff(), scales.force), 1e-300);
  double excess = 0.0;
  if (onPlane()) {
    for (Eigen::Index i = 0; i < s.force.rows(); ++i)
      excess = std::max(excess, s.force.row(i).norm() - *p_.constant_limit);
    return {{"aft_force_error", s.psi.cwiseAbs().maxCoeff() / scale}, {"force_limit_excess", excess / scale}};
  }
  const Eigen::ArrayXd p = s.force.col(0).array();
  for (Eigen::Index i = 0; i < s.force.rows(); ++i)
    excess = std::max(excess, s.force.row(i).tail(m).norm() - p_.mu * std::max(p[i], 0.0));
  return {{"aft_force_error", s.psi.cwiseAbs().maxCoeff() / scale},
          {"negative_pressure", std::max(0.0, -p.minCoeff()) / scale},
          {"force_limit_excess", excess / scale}};
}

LocalVector ElasticFrictionAft::solveStep(const StepProblem& step) const {
  if (onPlane())
    return Jenkins(p_.tangents, *p_.constant_limit, p_.k_t,
                   p_.tangents == 1 ? FrictionForm::kMinMax : FrictionForm::kMax)
        .solveStep(step);
  // contact-friction's λ is −λ here, so its Delassus operator (the response
  // to its λ) is −delassus; its previous force carries the slider's state.
  StepProblem turned = step;
  turned.delassus = -step.delassus;
  turned.force_start = -step.force_start;
  return -step_law_->solveStep(turned);
}

std::optional<StaticStatus> ElasticFrictionAft::staticStatus(const LawSamples& rest) const {
  if (onPlane()) return frictionStatus(rest.force.row(0).norm(), *p_.constant_limit);
  const StaticStatus normal = normalContactStatus(p_.gap, rest);
  const double pressure = rest.force(0, 0);
  StaticStatus s = frictionStatus(rest.force.row(0).tail(p_.tangents).norm(), p_.mu * std::max(pressure, 0.0));
  if (normal.state == StaticStatus::State::kOpen) s.state = StaticStatus::State::kOpen;
  s.gap = normal.gap;
  s.normal_force = normal.normal_force;
  return s;
}

std::shared_ptr<Law> ElasticFrictionAft::anchoredAt(const LawSamples& rest) const {
  double w[kMaxTangents] = {0.0, 0.0}, u_t[kMaxTangents] = {0.0, 0.0};
  for (int a = 0; a < p_.tangents; ++a) u_t[a] = rest.displacement(0, firstTangent() + a);
  returnMap(p_, rest.displacement(0, 0), u_t, w);
  auto out = std::make_shared<ElasticFrictionAft>(*this);
  out->anchor_.assign(w, w + p_.tangents);
  for (double x : out->anchor_)
    if (!std::isfinite(x)) throwInputError("preload", formatNumber(x), "a slider's static position must be finite");
  return out;
}

}  // namespace eqhb
