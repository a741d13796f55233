// Elastic dry friction on one DOF in the alternating frequency–time form
// (formulation = "aft"): the force is computed from the displacement over the
// period by the return map of sliders in parallel, each a spring k_s in
// series with a Coulomb slider of limit μN_s (one slider: the Jenkins
// element of jenkins.h; several: an Iwan element), and the law is
//   Ψ(t_i) = λ(t_i) − F[x](t_i),   F = Σ_s F_s,
// which is not pointwise in time: F at t_i reads x back to the slider's last
// slip. Per slider, with state w (the slider's position):
//   trial  T = −k_s (x_i − w);
//   stick  |T| <= μN_s: F_s = T;
//   slip   |T| >  μN_s: F_s = μN_s sign T and w = x_i + F_s/k_s.
// The map runs over the period twice from w = x̄ (the period's mean of x):
// one pass with a slip leaves a state that no longer depends on where it
// started (a slider is a play operator: a slip sets w from x alone), so the
// second pass is periodic. A slider that never slips keeps w = x̄: its force
// is −k_s (x − x̄), mean-free, so a period that sticks throughout is the
// linear structure with k_s added at every harmonic but the constant one
// (the stuck slider's position is not fixed by a periodic orbit; the mean is
// the choice that adds no static force of its own).
//
// Anchored (anchoredAt, after a static preload): each slider starts the
// first pass at its static position w_s instead of x̄, so a slider that
// never slips keeps w_s and its force −k_s (x − w_s) carries the static
// force; a slider that slips forgets w_s as above.
//
// Jacobian (exact, almost everywhere): stick since the slip at sample s,
// ∂F_i/∂x_j = −k_s (δ_ij − δ_js) (δ_js → 1/N for a slider that never
// slipped); slip, 0. The law thus has one history term per slider.
#pragma once

#include <vector>

#include "eqhb/laws/law.h"

namespace eqhb {

class JenkinsAft : public Law {
 public:
  struct Slider {
    double mu_n, k_t;
  };
  // Throws InputError naming the field: at least one slider; each μN >= 0,
  // k_t > 0, all finite. `type`: the registered name of the law it is the
  // form of ("jenkins"; "iwan", laws/joints/iwan_sliders.h).
  explicit JenkinsAft(std::vector<Slider> sliders, std::string type = "jenkins");
  std::string type() const override { return type_; }
  int dimension() const override { return 1; }
  bool usesDisplacement() const override { return true; }
  bool usesVelocity() const override { return false; }
  int historyTerms() const override { return static_cast<int>(sliders_.size()); }
  double forceLevel() const override { return total_limit_; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  // The same with the first pass started at `anchors` (one per slider)
  // instead of the law's own start: for a reader of another law's orbit
  // (the exact Jenkins law's slider, whose position the harmonic balance
  // gives), without a copy of the law per orbit.
  void evaluateFrom(const double* anchors, LawSamples& samples, bool with_derivatives) const;
  // aft_force_error max |λ − F[x]| and force_limit_excess max(|λ|/ΣμN − 1, 0),
  // relative to the larger of max|λ| and the problem's force scale's floor.
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // One slider: the Jenkins element's exact step (jenkins.h); more sliders
  // need a state each, which the reference integrator does not carry.
  LocalVector solveStep(const StepProblem& step) const override;
  // The static step from rest is the anchored law at w = 0 (anchors of
  // zeros): on one sample, a slider sticks with −k_s x or slips at ±μN_s.
  bool rateIndependent() const override { return true; }
  std::optional<StaticStatus> staticStatus(const LawSamples& rest) const override;
  // A copy whose sliders start at their state after the static step from
  // w = 0 to the displacement of `rest` (the return map of one sample).
  std::shared_ptr<Law> anchoredAt(const LawSamples& rest) const override;
  // The same with the sliders' positions given (one per slider, finite).
  std::shared_ptr<JenkinsAft> withAnchors(std::vector<double> positions) const;
  const std::vector<Slider>& sliders() const { return sliders_; }
  const std::vector<double>& anchors() const { return anchors_; }
  double muN() const { return total_limit_; }

 private:
  std::vector<Slider> sliders_;
  std::string type_;
  double total_limit_ = 0.0;
  std::vector<double> anchors_;  // empty: not anchored (start at x̄)
};

}  // namespace eqhb
