#include "eqhb/laws/joints/iwan_sliders.h"

#include <cmath>

#include "eqhb/error.h"

namespace eqhb {

namespace {
// (χ+1)/(χ+2): F_S / (K_T φ_max) of the power-law part alone.
double shape(const IwanParameters& p) { return (p.chi + 1.0) / (p.chi + 2.0); }
}  // namespace

double iwanMaxSlipDisplacement(const IwanParameters& p) {
  return p.slip_force * (1.0 + p.beta) / (p.stiffness * (p.beta + shape(p)));
}

std::vector<JenkinsAft::Slider> iwanSliders(const IwanParameters& p) {
  if (!(p.slip_force > 0.0) || !std::isfinite(p.slip_force))
    throwInputError("muN", formatNumber(p.slip_force), "slip force must be finite and > 0");
  if (!(p.stiffness > 0.0) || !std::isfinite(p.stiffness))
    throwInputError("k_t", formatNumber(p.stiffness), "stiffness must be finite and > 0");
  if (!(p.chi > -1.0) || !(p.chi <= 10.0)) throwInputError("chi", formatNumber(p.chi), "must be in (-1, 10]");
  if (!(p.beta >= 0.0) || !std::isfinite(p.beta)) throwInputError("beta", formatNumber(p.beta), "must be >= 0");
  if (p.cells < 1 || p.cells > 10000) throwInputError("sliders", std::to_string(p.cells), "must be in [1, 10000]");
  const double phi_max = iwanMaxSlipDisplacement(p);
  const double denominator = p.beta + shape(p);
  const double e1 = p.chi + 1.0, e2 = p.chi + 2.0;
  // The cumulative stiffness R φ^{χ+1}/(χ+1) and slip force R φ^{χ+2}/(χ+2)
  // written in s = φ/φ_max, so that no power of φ_max over- or underflows.
  const double k_power = p.slip_force / (phi_max * denominator);  // R φ_max^{χ+1} / (χ+1)
  const double f_power = p.slip_force * shape(p) / denominator;  // R φ_max^{χ+2} / (χ+2)
  std::vector<JenkinsAft::Slider> sliders;
  double previous_k = 0.0, previous_f = 0.0;
  for (int j = 1; j <= p.cells; ++j) {
    const double s = static_cast<double>(j) / p.cells;
    const double k = k_power * std::pow(s, e1), f = f_power * std::pow(s, e2);
    sliders.push_back({f - previous_f, k - previous_k});
    previous_k = k;
    previous_f = f;
  }
  if (p.beta > 0.0) {
    const double s_weight = p.slip_force * p.beta / (phi_max * denominator);
    sliders.push_back({s_weight * phi_max, s_weight});
  }
  return sliders;
}

}  // namespace eqhb
