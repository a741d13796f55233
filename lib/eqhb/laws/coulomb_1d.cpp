#include "eqhb/laws/coulomb_1d.h"

#include <algorithm>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/laws/form_names.h"
#include "eqhb/laws/dissipation_deficit.h"
#include "eqhb/laws/joints/friction_kernels.h"

namespace eqhb {

namespace {
constexpr FormName<CoulombForm> kCoulombFormNames[] = {
    {CoulombForm::kMinMax, "minmax"}, {CoulombForm::kProjection, "projection"}, {CoulombForm::kTanh, "tanh"},
    {CoulombForm::kPiecewise, "piecewise"}};
}  // namespace

CoulombForm parseCoulombForm(const std::string& name) {
  return parseForm(kCoulombFormNames, name, "form");
}

std::string coulombFormName(CoulombForm form) { return formName(kCoulombFormNames, form); }

namespace {
// The scale-free slope: 1/β = the scale-free width (law.h).
// A limit so small that the slope overflows (μN = 5e-320) applies no force a
// width could matter for: the absolute measure's slope then.
double scaleFreeBeta(const LawScales& scales, double mu_n) {
  const double beta = 1.0 / scaleFreeVelocityWidth(scales, mu_n);
  return std::isfinite(beta) ? beta : 1.0 / kScaleFreeWidthFraction;
}
}  // namespace

Coulomb1D::Coulomb1D(double mu_n, CoulombForm form, RhoSetting rho, std::optional<double> beta)
    : mu_n_(mu_n),
      form_(form),
      rho_setting_(rho),
      rho_(rho.value),
      beta_scale_free_(!beta),
      beta_(beta ? *beta : scaleFreeBeta(LawScales{}, mu_n)),
      creep_width_(1.0 / scaleFreeBeta(LawScales{}, mu_n)) {
  if (!(mu_n >= 0.0) || !std::isfinite(mu_n))
    throwInputError("muN", formatNumber(mu_n), "friction limit must be finite and >= 0");
  if (!(rho_ > 0.0) || !std::isfinite(rho_)) throwInputError(rho.field(), formatNumber(rho_), "must be finite and > 0");
  if (!(beta_ > 0.0) || !std::isfinite(beta_))
    throwInputError("beta", formatNumber(beta_), "regularisation slope must be finite and > 0");
}

double reversingStepForce(double v_start, double u_free, double delassus, double limit, double projected) {
  if (v_start == 0.0 || !(limit > 0.0)) return projected;
  const double s = v_start > 0.0 ? 1.0 : -1.0;
  const double u_old = u_free - s * delassus * limit;  // end velocity under the old slip force
  if (s * u_old > 0.0) return projected;               // still sliding the old way at the end
  // The mean force that keeps the velocity from changing: within the limit,
  // the mass stops and sticks, and u_end = 0 (the projection) is exact.
  const double hold = (v_start - u_free) / delassus;
  if (std::abs(hold) <= limit) return projected;
  const double phi = v_start / (v_start - u_old);  // in (0, 1]: s u_old <= 0 < s v_start
  return s * limit * (1.0 - 2.0 * phi);
}

LocalVector Coulomb1D::solveStep(const StepProblem& step) const {
  LocalVector force(1);
  const double d = step.delassus(0, 0), u_free = step.u_free[0];
  force[0] = reversingStepForce(step.v_start[0], u_free, d, mu_n_, std::clamp(-u_free / d, -mu_n_, mu_n_));
  return force;
}

std::vector<std::pair<std::string, double>> Coulomb1D::violations(const LawSamples& s,
                                                                  const PhysicalScales& scales) const {
  return frictionViolations(s.velocity.col(0), s.force.col(0), Eigen::VectorXd::Constant(s.force.rows(), mu_n_),
                            scales.velocity, regularised() ? creep_width_ : 0.0);
}

std::vector<std::pair<std::string, double>> frictionViolations(
    const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& r,
    const Eigen::Ref<const Eigen::VectorXd>& limit, double velocity_scale, double creep) {
  // A fully stuck contact has v ≡ 0 up to rounding: against max|v| alone
  // every sample of that noise would count as sliding.
  const double v_scale = invariantScale(v.cwiseAbs().maxCoeff(), velocity_scale);
  double excess = 0.0, sliding = 0.0;
  DissipationDeficit deficit;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (limit[i] <= 0.0) continue;
    excess = std::max(excess, std::abs(r[i]) / limit[i] - 1.0);
    if (std::abs(v[i]) <= creep) continue;  // a regularised form's stand-in for sticking
    if (std::abs(v[i]) > kSlidingFraction * v_scale)  // clearly sliding: r = −L sign(v)
      sliding = std::max(sliding, std::abs(r[i] + std::copysign(limit[i], v[i])) / limit[i]);
    deficit.add(r[i] * v[i], limit[i] * std::abs(v[i]));
  }
  const double floor = kSlidingFraction * static_cast<double>(v.size()) * limit.maxCoeff() * v_scale;
  return {{"force_limit_excess", excess},
          {"sliding_force_error", sliding},
          {"dissipation_deficit", deficit.value(floor)}};
}

void Coulomb1D::evaluate(LawSamples& s, bool with_derivatives) const {
  const Eigen::Index n = s.psi.rows();
  const double* v = s.velocity.data();
  const double* r = s.force.data();
  double* psi = s.psi.data();
  double* dv = s.dpsi_dvelocity.data();
  double* dr = s.dpsi_dforce.data();
  switch (form_) {
    case CoulombForm::kMinMax:
      for (Eigen::Index i = 0; i < n; ++i) {
        const MinMaxBranch branch = minMaxBranch(rho_, v[i], r[i], mu_n_);
        psi[i] = branch.psi;
        if (with_derivatives) {
          const double lower = branch.lower ? 1.0 : 0.0;  // min branch active
          const double upper = branch.upper ? 1.0 : 0.0;  // max branch active
          dv[i] = 1.0 - lower - upper;               // H(a) − H(b)
          dr[i] = rho_ * (lower + upper);            // ρ(1 − H(a) + H(b))
        }
      }
      break;
    case CoulombForm::kProjection:
      for (Eigen::Index i = 0; i < n; ++i) {
        const double trial = r[i] - rho_ * v[i];
        const bool inside = std::abs(trial) <= mu_n_;
        psi[i] = inside ? rho_ * v[i] : r[i] - std::copysign(mu_n_, trial);
        if (with_derivatives) {
          dv[i] = inside ? rho_ : 0.0;
          dr[i] = inside ? 0.0 : 1.0;
        }
      }
      break;
    case CoulombForm::kTanh:
      for (Eigen::Index i = 0; i < n; ++i) {
        const double t = std::tanh(beta_ * v[i]);
        psi[i] = r[i] + mu_n_ * t;
        if (with_derivatives) {
          dv[i] = mu_n_ * beta_ * (1.0 - t * t);
          dr[i] = 1.0;
        }
      }
      break;
    case CoulombForm::kPiecewise:
      for (Eigen::Index i = 0; i < n; ++i) {
        const double bv = beta_ * v[i];
        const bool linear = std::abs(bv) < 1.0;
        psi[i] = r[i] + mu_n_ * (linear ? bv : std::copysign(1.0, bv));
        if (with_derivatives) {
          dv[i] = linear ? mu_n_ * beta_ : 0.0;
          dr[i] = 1.0;
        }
      }
      break;
  }
}

std::optional<Law::RhoComparison> Coulomb1D::compareRho(const LawScales& scales) const {
  if (form_ == CoulombForm::kTanh || form_ == CoulombForm::kPiecewise) return std::nullopt;
  const double mobility = scales.mobility();
  return RhoComparison{rho_, kScaleFreeRhoWeight * (form_ == CoulombForm::kMinMax ? mobility : 1.0 / mobility)};
}

std::optional<WidthComparison> Coulomb1D::compareWidth(const LawScales& scales) const {
  if (!regularised()) return std::nullopt;
  return WidthComparison{"beta", beta_, scaleFreeBeta(scales, mu_n_)};
}

std::shared_ptr<Law> Coulomb1D::withScaleFreeRho(const LawScales& scales) const {
  const auto rho = compareRho(scales);
  const bool set_rho = rho_setting_.scale_free && rho;
  if (!set_rho && !regularised()) return nullptr;
  auto copy = std::make_shared<Coulomb1D>(*this);
  if (set_rho) copy->rho_ = rho_setting_.factor * rho->scale_free;
  if (regularised()) copy->creep_width_ = 1.0 / scaleFreeBeta(scales, mu_n_);
  if (regularised() && beta_scale_free_) copy->beta_ = scaleFreeBeta(scales, mu_n_);
  return copy;
}

double Coulomb1D::residualScale(const PhysicalScales& s, int) const {
  switch (form_) {
    case CoulombForm::kMinMax: return std::min(s.velocity, rho_ * s.force);     // v and ρ r
    case CoulombForm::kProjection: return std::min(rho_ * s.velocity, s.force);  // ρ v and r
    case CoulombForm::kTanh:
    case CoulombForm::kPiecewise: break;
  }
  return s.force;  // r + μN φ(v)
}

std::optional<StaticStatus> Coulomb1D::staticStatus(const LawSamples& rest) const {
  return frictionStatus(std::abs(rest.force(0, 0)), mu_n_);
}

}  // namespace eqhb
