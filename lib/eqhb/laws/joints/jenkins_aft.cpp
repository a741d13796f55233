#include "eqhb/laws/joints/jenkins_aft.h"

#include <cmath>
#include <stdexcept>

#include "eqhb/error.h"
#include "eqhb/laws/joints/friction_kernels.h"
#include "eqhb/laws/joints/jenkins.h"

namespace eqhb {

JenkinsAft::JenkinsAft(std::vector<Slider> sliders, std::string type)
    : sliders_(std::move(sliders)), type_(std::move(type)) {
  if (sliders_.empty()) throwInputError("sliders", "0", "an element needs at least one slider");
  for (const Slider& s : sliders_) {
    if (!(s.mu_n >= 0.0) || !std::isfinite(s.mu_n))
      throwInputError("muN", formatNumber(s.mu_n), "friction limit must be finite and >= 0");
    if (!(s.k_t > 0.0) || !std::isfinite(s.k_t))
      throwInputError("k_t", formatNumber(s.k_t), "tangential stiffness must be finite and > 0");
    total_limit_ += s.mu_n;
  }
}

namespace {
// One slider's return map at sample i from state w: the force; on a slip
// (`slipped`), w and `anchor` (the sample that now fixes w) move.
inline double returnMap(const JenkinsAft::Slider& s, double x, int i, double& w, int& anchor, bool& slipped) {
  const double trial = -s.k_t * (x - w);
  slipped = std::abs(trial) > s.mu_n;
  if (!slipped) return trial;
  const double force = std::copysign(s.mu_n, trial);
  w = x + force / s.k_t;
  anchor = i;
  return force;
}
}  // namespace

void JenkinsAft::evaluate(LawSamples& s, bool with_derivatives) const {
  evaluateFrom(anchors_.empty() ? nullptr : anchors_.data(), s, with_derivatives);
}

void JenkinsAft::evaluateFrom(const double* anchors, LawSamples& s, bool with_derivatives) const {
  const int n = static_cast<int>(s.psi.rows());
  const int terms = historyTerms();
  if (with_derivatives && s.history_weight.cols() != terms)
    throw std::logic_error("JenkinsAft: samples sized without history terms (LawSamples::resize)");
  const auto x = s.displacement.col(0);
  const double mean = x.mean();
  s.psi.col(0) = s.force.col(0);
  if (with_derivatives) {
    s.dpsi_dforce.col(0).setOnes();
    s.dpsi_ddisplacement.col(0).setZero();
  }
  for (int k = 0; k < terms; ++k) {
    const Slider& slider = sliders_[k];
    // Pass 1 from the mean, or from the static anchor: only the state at
    // its end matters. kFixed: w is a constant (no dependence on x).
    constexpr int kFixed = -2;
    const bool anchored = anchors != nullptr;
    double w = anchored ? anchors[k] : mean;
    int anchor = anchored ? kFixed : LawSamples::kPeriodMean;
    bool slipped = false;
    for (int i = 0; i < n; ++i) returnMap(slider, x[i], i, w, anchor, slipped);
    // Pass 2: periodic (see the header); Ψ = λ − F.
    for (int i = 0; i < n; ++i) {
      const double force = returnMap(slider, x[i], i, w, anchor, slipped);
      s.psi(i, 0) -= force;
      if (!with_derivatives) continue;
      // Stick: ∂Ψ_i/∂x_i = k, ∂Ψ_i/∂x_anchor = −k (the anchor may be i
      // itself, a slip of the first pass at this sample: the force is the
      // limit, its derivative 0 as the two terms cancel).
      const bool moved = !slipped && anchor != kFixed;  // stuck since a slip or x̄
      s.dpsi_ddisplacement(i, 0) += slipped ? 0.0 : slider.k_t;
      s.history_sample(i, k) = moved ? anchor : i;
      s.history_weight(i, k) = moved ? -slider.k_t : 0.0;
    }
  }
}

std::vector<std::pair<std::string, double>> JenkinsAft::violations(const LawSamples& samples,
                                                                   const PhysicalScales& scales) const {
  LawSamples s = samples;  // not a hot path: the law is evaluated again on a copy
  evaluate(s, false);
  const double scale = std::max(invariantScale(s.force.col(0).cwiseAbs().maxCoeff(), scales.force), 1e-300);
  const double excess =
      total_limit_ > 0.0 ? std::max(0.0, s.force.col(0).cwiseAbs().maxCoeff() / total_limit_ - 1.0) : 0.0;
  return {{"aft_force_error", s.psi.col(0).cwiseAbs().maxCoeff() / scale}, {"force_limit_excess", excess}};
}

LocalVector JenkinsAft::solveStep(const StepProblem& step) const {
  if (sliders_.size() != 1)
    throw InputError("law " + type_ + ": the time reference carries one state per law, and an element of " +
                     std::to_string(sliders_.size()) + " sliders has as many");
  return Jenkins(1, sliders_[0].mu_n, sliders_[0].k_t, FrictionForm::kMinMax).solveStep(step);
}

std::shared_ptr<JenkinsAft> JenkinsAft::withAnchors(std::vector<double> positions) const {
  if (positions.size() != sliders_.size())
    throw std::invalid_argument("JenkinsAft::withAnchors: one position per slider");
  for (double w : positions)
    if (!std::isfinite(w)) throwInputError("preload", formatNumber(w), "a slider's static position must be finite");
  auto out = std::make_shared<JenkinsAft>(*this);
  out->anchors_ = std::move(positions);
  return out;
}

std::shared_ptr<Law> JenkinsAft::anchoredAt(const LawSamples& rest) const {
  std::vector<double> positions;
  const double x = rest.displacement(0, 0);
  for (const Slider& slider : sliders_) {
    double w = 0.0;
    int anchor = 0;
    bool slipped = false;
    returnMap(slider, x, 0, w, anchor, slipped);
    positions.push_back(w);
  }
  return withAnchors(std::move(positions));
}

std::optional<StaticStatus> JenkinsAft::staticStatus(const LawSamples& rest) const {
  return frictionStatus(std::abs(rest.force(0, 0)), total_limit_);
}

}  // namespace eqhb
