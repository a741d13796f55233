#include "eqhb/laws/signorini.h"
#include "eqhb/laws/contact_status.h"

#include <algorithm>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/laws/scale_free_copy.h"
#include "eqhb/laws/form_names.h"

namespace eqhb {

namespace {
constexpr FormName<SignoriniForm> kSignoriniFormNames[] = {
    {SignoriniForm::kMin, "min"}, {SignoriniForm::kFischerBurmeister, "fischer-burmeister"},
    {SignoriniForm::kSignSquare, "sign-square"}};
}  // namespace

SignoriniForm parseSignoriniForm(const std::string& name) {
  return parseForm(kSignoriniFormNames, name, "form");
}

std::string signoriniFormName(SignoriniForm form) { return formName(kSignoriniFormNames, form); }

Signorini::Signorini(double gap, SignoriniForm form, RhoSetting rho)
    : gap_(gap), form_(form), rho_setting_(rho), rho_(rho.value) {
  if (!std::isfinite(gap)) throwInputError("gap", formatNumber(gap), "must be finite (no NaN or Inf)");
  if (!(rho_ > 0.0) || !std::isfinite(rho_)) throwInputError(rho.field(), formatNumber(rho_), "must be finite and > 0");
}

void Signorini::evaluate(LawSamples& s, bool with_derivatives) const {
  const Eigen::Index n = s.psi.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double a = rho_ * (gap_ - s.displacement(i, 0));  // ∂a/∂x = −ρ
    const double p = s.force(i, 0);
    double psi = 0.0, da = 0.0, dp = 0.0;
    switch (form_) {
      case SignoriniForm::kMin:
        if (a < p) {
          psi = a, da = 1.0, dp = 0.0;
        } else {
          psi = p, da = 0.0, dp = 1.0;
        }
        break;
      case SignoriniForm::kFischerBurmeister: {
        const double root = std::hypot(a, p);
        psi = a + p - root;
        if (root > 0.0) {
          da = 1.0 - a / root;
          dp = 1.0 - p / root;
        } else {
          da = dp = 1.0 - std::sqrt(0.5);
        }
        break;
      }
      case SignoriniForm::kSignSquare:
        psi = -(a - p) * (a - p) + std::abs(a) * a + std::abs(p) * p;
        da = -2.0 * (a - p) + 2.0 * std::abs(a);
        dp = 2.0 * (a - p) + 2.0 * std::abs(p);
        break;
    }
    s.psi(i, 0) = psi;
    if (with_derivatives) {
      s.dpsi_ddisplacement(i, 0) = -rho_ * da;
      s.dpsi_dforce(i, 0) = dp;
    }
  }
}

LocalVector Signorini::solveStep(const StepProblem& step) const {
  LocalVector pressure(1);
  pressure[0] = 0.0;
  const double gap = gap_ - step.x_start[0];
  const double gap_rate = -step.v_start[0];  // ġ = −ẋ
  if (gap + 0.5 * step.h * gap_rate > 0.0) return pressure;  // stays open
  // ġ_end = −u_end = −u_free − D p, with D = −h G (force −p): ġ_end = −u_free + h G p.
  const double stiffness = -step.delassus(0, 0);  // h G > 0
  pressure[0] = std::max(0.0, (step.u_free[0] - step.restitution * gap_rate) / stiffness);
  return pressure;
}

std::vector<std::pair<std::string, double>> Signorini::violations(const LawSamples& s,
                                                                  const PhysicalScales& scales) const {
  const Eigen::ArrayXd g = gap_ - s.displacement.col(0).array();
  const Eigen::ArrayXd p = s.force.col(0).array();
  // A wall never touched has p ≡ 0 up to rounding (1e-13): against max|p|
  // alone that noise would read as a pulling wall.
  const double g_scale = invariantScale(g.abs().maxCoeff(), scales.displacement),
               p_scale = invariantScale(p.abs().maxCoeff(), scales.force);
  auto relative = [](double value, double scale) { return scale > 0.0 ? value / scale : 0.0; };
  return {{"penetration", relative(std::max(0.0, -g.minCoeff()), g_scale)},
          {"negative_pressure", relative(std::max(0.0, -p.minCoeff()), p_scale)},
          {"complementarity", relative((g * p).abs().maxCoeff(), g_scale * p_scale)}};
}

std::optional<Law::RhoComparison> Signorini::compareRho(const LawScales& scales) const {
  return RhoComparison{rho_, kScaleFreeRhoWeight / scales.compliance};
}

std::shared_ptr<Law> Signorini::withScaleFreeRho(const LawScales& scales) const {
  return copyWithScaleFreeRho(*this, rho_setting_, &Signorini::rho_, scales);
}

double Signorini::residualScale(const PhysicalScales& s, int) const {
  const double scale = std::min(rho_ * s.displacement, s.force);  // ρ g and p
  return form_ == SignoriniForm::kSignSquare ? scale * scale : scale;
}

std::optional<StaticStatus> Signorini::staticStatus(const LawSamples& rest) const {
  return normalContactStatus(gap_, rest);
}

}  // namespace eqhb
