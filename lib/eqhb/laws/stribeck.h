// Stribeck friction on one DOF (spec §2): velocity-weakening limit
//   L(v) = μ_d N + (μ_s − μ_d) N exp(−|v| / v_s),
//   Ψ = v + min(0, ρ(r + L(v)) − v) + max(0, ρ(r − L(v)) − v).
// L is not differentiable at v = 0; its weak derivative there is taken as 0.
#pragma once

#include "eqhb/laws/law.h"

namespace eqhb {

class Stribeck : public Law {
 public:
  // Throws InputError: 0 <= μ_d N <= μ_s N, v_s > 0, ρ > 0, all finite.
  Stribeck(double mu_n_dynamic, double mu_n_static, double v_s, RhoSetting rho = {});
  std::string type() const override { return "stribeck"; }
  int dimension() const override { return 1; }
  bool usesDisplacement() const override { return false; }
  bool usesVelocity() const override { return true; }
  // Its static step reads the increment as a speed over a unit time: a stuck
  // contact (increment 0) is held to the static limit μ(0).
  bool rateIndependent() const override { return true; }
  bool oddSymmetric() const override { return true; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  double forceLevel() const override { return dynamic_ + drop_; }
  double residualScale(const PhysicalScales& scales, int component) const override;
  // As Coulomb1D, with the limit L(v) of each sample.
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // Stick if |u_free| <= D L(0); else slide with w = |u_end| > 0 solving
  // w = |u_free| − D L(v_θ) (bracketed bisection–Newton), λ = −L(v_θ) sign(u_free),
  // v_θ = θ u_end + (1 − θ) v_start the velocity of the θ-method's forces;
  // a reversal inside the step holds the mean force (reversingStepForce).
  LocalVector solveStep(const StepProblem& step) const override;
  // The minmax form compares v with ρr: ρ = ω|G|.
  std::shared_ptr<Law> withScaleFreeRho(const LawScales& scales) const override;
  std::optional<RhoComparison> compareRho(const LawScales& scales) const override;
  double limit(double v) const;
  double dynamicLimit() const { return dynamic_; }        // μ_d N
  double staticLimit() const { return dynamic_ + drop_; }  // μ_s N = L(0)
  double slidingVelocity() const { return v_s_; }         // v_s

 private:
  // λ without the reversal: stick if |u_free| <= D L(0), else slide.
  double stickOrSlideForce(double u_free, double v_start, double d, double theta) const;
  double dynamic_, drop_, v_s_;
  RhoSetting rho_setting_;
  double rho_;
};

}  // namespace eqhb
