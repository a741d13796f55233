#include "eqhb/laws/coulomb_2d.h"

#include <algorithm>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/laws/form_names.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/dissipation_deficit.h"

namespace eqhb {

namespace {
constexpr FormName<Coulomb2DForm> kCoulomb2DFormNames[] = {
    {Coulomb2DForm::kMax, "max"}, {Coulomb2DForm::kProjection, "projection"},
    {Coulomb2DForm::kSmoothed, "smoothed"}, {Coulomb2DForm::kTanh, "tanh"}};
}  // namespace

Coulomb2DForm parseCoulomb2DForm(const std::string& name) {
  return parseForm(kCoulomb2DFormNames, name, "form");
}

std::string coulomb2DFormName(Coulomb2DForm form) { return formName(kCoulomb2DFormNames, form); }

Coulomb2D::Coulomb2D(double mu_n, Coulomb2DForm form, RhoSetting rho, std::optional<double> epsilon,
                     std::optional<double> alpha)
    : mu_n_(mu_n),
      form_(form),
      rho_setting_(rho),
      rho_(rho.value),
      width_scale_free_(form == Coulomb2DForm::kSmoothed ? !epsilon : form == Coulomb2DForm::kTanh && !alpha) {
  const double unit = scaleFreeWidth(LawScales{});  // the form's own width, at unit scales
  epsilon_ = epsilon ? *epsilon : form == Coulomb2DForm::kSmoothed ? unit : 1e-4;
  alpha_ = alpha ? *alpha : form == Coulomb2DForm::kTanh ? unit : 1.0;
  if (form == Coulomb2DForm::kTanh) creep_width_ = 1.0 / unit;
  if (!(mu_n >= 0.0) || !std::isfinite(mu_n))
    throwInputError("muN", formatNumber(mu_n), "friction limit must be finite and >= 0");
  if (!(rho_ > 0.0) || !std::isfinite(rho_)) throwInputError(rho.field(), formatNumber(rho_), "must be finite and > 0");
  if (!(epsilon_ > 0.0) || !std::isfinite(epsilon_))
    throwInputError("epsilon", formatNumber(epsilon_), "smoothing must be finite and > 0");
  if (!(alpha_ > 0.0) || !std::isfinite(alpha_))
    throwInputError("alpha", formatNumber(alpha_), "tanh slope must be finite and > 0");
}

void Coulomb2D::evaluate(LawSamples& s, bool with_derivatives) const {
  const Eigen::Index n = s.psi.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d r(s.force(i, 0), s.force(i, 1));
    const Eigen::Vector2d v(s.velocity(i, 0), s.velocity(i, 1));
    const Eigen::Vector2d trial = r - rho_ * v;
    Eigen::Vector2d psi;
    Eigen::Matrix2d dr = Eigen::Matrix2d::Zero(), dv = Eigen::Matrix2d::Zero();
    const Eigen::Matrix2d identity = Eigen::Matrix2d::Identity();
    switch (form_) {
      case Coulomb2DForm::kMax:
      case Coulomb2DForm::kSmoothed: {
        const double norm = form_ == Coulomb2DForm::kMax ? trial.norm()
                                                         : std::sqrt(trial.squaredNorm() + epsilon_);
        if (norm <= mu_n_) {  // sticking: Ψ = μN ρ v
          psi = mu_n_ * rho_ * v;
          dv = mu_n_ * rho_ * identity;
        } else {  // sliding: Ψ = r ‖s‖ − μN s, ∂‖s‖/∂s = sᵀ/‖s‖
          psi = r * norm - mu_n_ * trial;
          dr = (norm - mu_n_) * identity + r * trial.transpose() / norm;
          dv = mu_n_ * rho_ * identity - rho_ * r * trial.transpose() / norm;
        }
        break;
      }
      case Coulomb2DForm::kProjection: {
        const double norm = trial.norm();
        if (norm <= mu_n_) {  // Ψ = ρ v
          psi = rho_ * v;
          dv = rho_ * identity;
        } else {  // Ψ = r − μN s/‖s‖
          const Eigen::Matrix2d dproj =
              (mu_n_ / norm) * (identity - trial * trial.transpose() / (norm * norm));
          psi = r - mu_n_ * trial / norm;
          dr = identity - dproj;
          dv = rho_ * dproj;
        }
        break;
      }
      case Coulomb2DForm::kTanh: {
        const double speed = v.norm();
        const double t = std::tanh(alpha_ * speed);
        psi = r * speed + mu_n_ * t * v;
        dr = speed * identity;
        if (speed > 0.0)
          dv = r * v.transpose() / speed + mu_n_ * t * identity +
               mu_n_ * alpha_ * (1.0 - t * t) * v * v.transpose() / speed;
        break;
      }
    }
    s.psi(i, 0) = psi[0];
    s.psi(i, 1) = psi[1];
    if (!with_derivatives) continue;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        s.dpsi_dforce(i, a * 2 + b) = dr(a, b);
        s.dpsi_dvelocity(i, a * 2 + b) = dv(a, b);
      }
  }
}

namespace {
Eigen::Vector2d projectOnDisc(const Eigen::Vector2d& x, double radius) {
  const double norm = x.norm();
  return norm <= radius ? x : Eigen::Vector2d(x * (radius / norm));
}
}  // namespace

LocalVector Coulomb2D::solveStep(const StepProblem& step) const {
  const Eigen::Matrix2d d = step.delassus;
  const Eigen::Vector2d u_free = step.u_free;
  // Step 1/L with L the largest eigenvalue of D: a contraction on the disc.
  const double largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(d).eigenvalues().maxCoeff();
  Eigen::Vector2d lambda = projectOnDisc(-u_free / largest, mu_n_);
  for (int iteration = 0; iteration < 10000; ++iteration) {
    const Eigen::Vector2d next = projectOnDisc(lambda - (d * lambda + u_free) / largest, mu_n_);
    const double change = (next - lambda).norm();
    lambda = next;
    if (change <= 1e-15 * std::max(mu_n_, 1e-300)) break;
  }
  LocalVector force(2);
  force << lambda[0], lambda[1];
  return force;
}

std::vector<std::pair<std::string, double>> Coulomb2D::violations(const LawSamples& s,
                                                                  const PhysicalScales& scales) const {
  double v_scale = 0.0;
  for (Eigen::Index i = 0; i < s.velocity.rows(); ++i) v_scale = std::max(v_scale, s.velocity.row(i).norm());
  v_scale = invariantScale(v_scale, scales.velocity);  // stuck: v ≡ 0 up to rounding
  double excess = 0.0, sliding = 0.0;
  if (mu_n_ <= 0.0) return {{"force_limit_excess", 0.0}, {"sliding_force_error", 0.0}, {"dissipation_deficit", 0.0}};
  DissipationDeficit deficit;
  for (Eigen::Index i = 0; i < s.force.rows(); ++i) {
    const Eigen::Vector2d r = s.force.row(i).transpose(), v = s.velocity.row(i).transpose();
    excess = std::max(excess, r.norm() / mu_n_ - 1.0);
    if (v.norm() <= creep_width_) continue;  // tanh's stand-in for sticking
    if (v.norm() > kSlidingFraction * v_scale)  // clearly sliding: r = −μN v/‖v‖
      sliding = std::max(sliding, (r + mu_n_ * v / v.norm()).norm() / mu_n_);
    deficit.add(r.dot(v), mu_n_ * v.norm());
  }
  const double floor = kSlidingFraction * static_cast<double>(s.force.rows()) * mu_n_ * v_scale;
  return {{"force_limit_excess", excess},
          {"sliding_force_error", sliding},
          {"dissipation_deficit", deficit.value(floor)}};
}

std::optional<Law::RhoComparison> Coulomb2D::compareRho(const LawScales& scales) const {
  if (form_ == Coulomb2DForm::kTanh) return std::nullopt;
  return RhoComparison{rho_, kScaleFreeRhoWeight / scales.mobility()};
}

double Coulomb2D::scaleFreeWidth(const LawScales& scales) const {
  if (form_ == Coulomb2DForm::kTanh) {
    const double alpha = 1.0 / scaleFreeVelocityWidth(scales, mu_n_);
    return std::isfinite(alpha) ? alpha : 1.0 / kScaleFreeWidthFraction;  // μN ~ 1e-320: immaterial
  }
  const double rounding = kScaleFreeWidthFraction * mu_n_;  // smoothed: √ε, a force
  const double epsilon = rounding * rounding;
  return epsilon > 0.0 && std::isfinite(epsilon) ? epsilon : 1e-4;  // μN = 0 (or ~1e-160): immaterial
}

std::optional<WidthComparison> Coulomb2D::compareWidth(const LawScales& scales) const {
  if (form_ == Coulomb2DForm::kSmoothed) return WidthComparison{"epsilon", epsilon_, scaleFreeWidth(scales)};
  if (form_ == Coulomb2DForm::kTanh) return WidthComparison{"alpha", alpha_, scaleFreeWidth(scales)};
  return std::nullopt;
}

std::shared_ptr<Law> Coulomb2D::withScaleFreeRho(const LawScales& scales) const {
  const auto rho = compareRho(scales);
  const bool set_rho = rho_setting_.scale_free && rho, tanh = form_ == Coulomb2DForm::kTanh;
  if (!set_rho && !width_scale_free_ && !tanh) return nullptr;
  auto copy = std::make_shared<Coulomb2D>(*this);
  if (set_rho) copy->rho_ = rho_setting_.factor * rho->scale_free;
  if (tanh) copy->creep_width_ = 1.0 / scaleFreeWidth(scales);
  if (width_scale_free_) (form_ == Coulomb2DForm::kTanh ? copy->alpha_ : copy->epsilon_) = scaleFreeWidth(scales);
  return copy;
}

double Coulomb2D::residualScale(const PhysicalScales& s, int) const {
  switch (form_) {
    case Coulomb2DForm::kMax:
    case Coulomb2DForm::kSmoothed: return s.force * std::min(s.force, rho_ * s.velocity);  // r‖s‖ and μN s
    case Coulomb2DForm::kProjection: return std::min(rho_ * s.velocity, s.force);         // ρ v and r
    case Coulomb2DForm::kTanh: break;
  }
  return s.force * s.velocity;  // r‖v‖ + μN tanh(α‖v‖) v
}

std::optional<StaticStatus> Coulomb2D::staticStatus(const LawSamples& rest) const {
  return frictionStatus(rest.force.row(0).norm(), mu_n_);
}

}  // namespace eqhb
