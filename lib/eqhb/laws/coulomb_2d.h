// Isotropic Coulomb friction in the plane (spec §2, "Coulomb 2D"), v = ẋ and
// r in R², s = r − ρ v:
//   max:        Ψ = r max(μN, ‖s‖) − μN s                      (exact)
//   projection: Ψ = r − proj_D(μN)(s)                          (exact)
//   smoothed:   the max form with ‖s‖ -> sqrt(‖s‖² + ε)        (ε > 0)
//   tanh:       Ψ = r ‖v‖ + μN tanh(α‖v‖) v                   (classical, stiff; α > 0)
// Ties (‖s‖ = μN) take the sticking branch. ε (a force squared) and α
// (1/velocity) are scale-free unless given (law.h): √ε = kScaleFreeWidthFraction · μN
// (the rounding moves the limit by a fraction ε/(2μN²) = 5e-5 of it) and
// 1/α = the scale-free width of the contact (scaleFreeVelocityWidth).
#pragma once

#include <optional>

#include "eqhb/laws/law.h"

namespace eqhb {

enum class Coulomb2DForm { kMax, kProjection, kSmoothed, kTanh };

Coulomb2DForm parseCoulomb2DForm(const std::string& name);
std::string coulomb2DFormName(Coulomb2DForm form);

class Coulomb2D : public Law {
 public:
  // Throws InputError: μN >= 0, ρ > 0, ε > 0, α > 0, all finite. Without ε
  // or α the form takes the scale-free one (at unit scales until a system
  // sets it, withScaleFreeRho).
  Coulomb2D(double mu_n, Coulomb2DForm form, RhoSetting rho = {}, std::optional<double> epsilon = std::nullopt,
            std::optional<double> alpha = std::nullopt);
  std::string type() const override { return "coulomb-2d"; }
  int dimension() const override { return 2; }
  bool usesDisplacement() const override { return false; }
  bool usesVelocity() const override { return true; }
  bool rateIndependent() const override { return true; }
  std::optional<StaticStatus> staticStatus(const LawSamples& rest) const override;
  bool oddSymmetric() const override { return true; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  double forceLevel() const override { return mu_n_; }
  double residualScale(const PhysicalScales& scales, int component) const override;
  // force_limit_excess: max(‖r‖/μN − 1, 0); sliding_force_error: max over
  // clearly sliding samples of ‖r + μN v/‖v‖‖ / μN; dissipation_deficit:
  // 1 − (Σ −r·v)/(Σ μN‖v‖) (dissipation_deficit.h).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // min over the disc ‖λ‖ <= μN of ½ λᵀDλ + λᵀu_free (maximal dissipation),
  // by projected gradient to round-off (exact projection when D = d I).
  LocalVector solveStep(const StepProblem& step) const override;
  // max, smoothed and projection compare r with ρv: ρ = 1/(ω|G|); tanh has
  // none. smoothed and tanh have a width (ε, α).
  std::shared_ptr<Law> withScaleFreeRho(const LawScales& scales) const override;
  std::optional<RhoComparison> compareRho(const LawScales& scales) const override;
  std::optional<WidthComparison> compareWidth(const LawScales& scales) const override;
  Coulomb2DForm form() const { return form_; }
  double muN() const { return mu_n_; }

 private:
  double mu_n_;
  Coulomb2DForm form_;
  RhoSetting rho_setting_;
  double rho_;
  bool width_scale_free_;  // no ε or α given for the form: set from the scales
  double epsilon_, alpha_;
  // tanh: the scale-free width 1/α at the scales last set, also when α is
  // given; slower slip is the creep that stands for sticking (Coulomb1D).
  double creep_width_ = 0.0;
  // The form's width (ε or α) from `scales` as the scale-free rule makes it.
  double scaleFreeWidth(const LawScales& scales) const;
};

}  // namespace eqhb
