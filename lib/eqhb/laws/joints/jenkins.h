// Elastic dry friction (Jenkins element, spec §5) on 1 or 2 DOFs: a spring
// k_t in series with a Coulomb slider w of limit μN. Force on the structure
// r = −k_t (x − w); the slider moves at ẇ = ẋ + ṙ/k_t, so the law is any
// exact Coulomb form of friction_kernels.h with slip velocity u = ẋ + ṙ/k_t
// and limit μN. Sticking is a state with stiffness k_t; k_t → ∞ gives the
// rigid Coulomb1D / Coulomb2D. (Under a varying normal load: ContactFriction
// with k_t.)
#pragma once

#include "eqhb/laws/joints/friction_kernels.h"
#include "eqhb/laws/law.h"

namespace eqhb {

class Jenkins : public Law {
 public:
  // Throws InputError naming the field: dimension 1 or 2, μN >= 0, k_t > 0,
  // ρ > 0, all finite; minmax only in 1D.
  Jenkins(int dimension, double mu_n, double k_t, FrictionForm form, RhoSetting rho = {});
  std::string type() const override { return "jenkins"; }
  int dimension() const override { return dimension_; }
  bool usesDisplacement() const override { return false; }
  bool usesVelocity() const override { return true; }
  bool rateIndependent() const override { return true; }
  std::optional<StaticStatus> staticStatus(const LawSamples& rest) const override;
  bool oddSymmetric() const override { return true; }
  bool usesForceRate() const override { return true; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  double forceLevel() const override { return mu_n_; }
  double muN() const { return mu_n_; }
  double stiffness() const { return 1.0 / compliance_; }  // k_t
  double residualScale(const PhysicalScales& scales, int component) const override;
  // force_limit_excess max(‖r‖/μN − 1, 0); sliding_force_error max over
  // samples clearly slipping (‖u‖ > kElasticSlidingFraction of max, u the
  // slider's velocity ẋ + ṙ/k_t) of ‖r + μN u/‖u‖‖/μN; dissipation_deficit
  // 1 − (Σ −r·u)/(Σ μN‖u‖) (dissipation_deficit.h).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // Implicit slider: with w_start = x_start + r_start/k_t, the force at the
  // end of the step minimises ½ rᵀ(hθD + I/k_t)r + rᵀ(x_pred − w_start)
  // over the disc ‖r‖ <= μN (maximal dissipation of the slip Δw).
  LocalVector solveStep(const StepProblem& step) const override;
  // The slider sees the structure and the spring in series: its mobility is
  // ω(|G| + 1/k_t), and ρ follows the form (scaleFreeFrictionRho).
  std::shared_ptr<Law> withScaleFreeRho(const LawScales& scales) const override;
  std::optional<RhoComparison> compareRho(const LawScales& scales) const override;

 private:
  int dimension_;
  double mu_n_, compliance_;
  FrictionForm form_;
  RhoSetting rho_setting_;
  double rho_;
};

}  // namespace eqhb
