// Coulomb friction on one DOF, r the friction force on the structure, v = ẋ
// (spec §2, "Coulomb 1D"). Exact forms (zero set = the Coulomb graph):
//   minmax:     Ψ = v + min(0, ρ(r+μN) − v) + max(0, ρ(r−μN) − v)
//   projection: Ψ = r − proj_[−μN, μN](r − ρ v)
// Regularised, single-valued forms (comparison only):
//   tanh:       Ψ = r + μN tanh(β v)
//   piecewise:  Ψ = r + μN clip(β v, −1, 1)
// β (1/velocity) is scale-free unless given: 1/β = the scale-free width of
// the contact (law.h, scaleFreeVelocityWidth).
// Weak derivatives take, at a tie (argument exactly on a kink), the branch
// that is constant: min(0, a) and max(0, b) count as 0, the projection as
// inside, clip as saturated.
#pragma once

#include <optional>
#include <string>

#include "eqhb/laws/law.h"

namespace eqhb {

enum class CoulombForm { kMinMax, kProjection, kTanh, kPiecewise };

CoulombForm parseCoulombForm(const std::string& name);

// Samples with |v| above this fraction of max|v| count as clearly sliding in
// the physical checks (transitions are left out: a truncated series cannot
// jump there).
constexpr double kSlidingFraction = 0.05;

// Checks shared by the 1D friction laws (limit per sample): see Coulomb1D.
// `velocity_scale`: the problem's V, the floor of max|v| (Law::violations).
// `creep`: slip speeds up to which a regularised form creeps where the exact
// law sticks (its scale-free width); those samples are no slip to check.
std::vector<std::pair<std::string, double>> frictionViolations(
    const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& r,
    const Eigen::Ref<const Eigen::VectorXd>& limit, double velocity_scale, double creep = 0.0);
std::string coulombFormName(CoulombForm form);

// The force held over a time step (Law::solveStep) of a 1D friction contact
// that slides at v_start and whose free end velocity is u_free (D the
// step's Delassus value, `limit` the friction limit near v = 0). When the
// old slip force takes the velocity through zero inside the step and the
// mass cannot stay at rest there (the force that holds it exceeds the
// limit), the contact REVERSES at the fraction φ = v_start / (v_start − u_old)
// of the step (u_old the end velocity under the old slip force), and the
// step holds the mean force φ(−s L) + (1 − φ)(s L), s = sign(v_start): the
// impulse of the step is then exact under a constant acceleration. Returns
// `projected` (the stick-or-slide choice on u_end) otherwise. Without it a
// reversal step ends at rest (a one-step stick the motion does not have) or
// slides all the step the new way: a velocity error of up to 2 L h / m per
// reversal, first order in h, whose size depends on where the reversal falls
// between two steps.
double reversingStepForce(double v_start, double u_free, double delassus, double limit, double projected);

class Coulomb1D : public Law {
 public:
  // Throws InputError: μN >= 0, ρ > 0, β > 0, all finite. Without β the
  // regularised forms take the scale-free one (at unit scales until a
  // system sets it, withScaleFreeRho).
  Coulomb1D(double mu_n, CoulombForm form, RhoSetting rho = {}, std::optional<double> beta = std::nullopt);

  std::string type() const override { return "coulomb-1d"; }
  int dimension() const override { return 1; }
  bool usesDisplacement() const override { return false; }
  bool usesVelocity() const override { return true; }
  bool rateIndependent() const override { return true; }
  std::optional<StaticStatus> staticStatus(const LawSamples& rest) const override;
  bool oddSymmetric() const override { return true; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  double forceLevel() const override { return mu_n_; }
  double residualScale(const PhysicalScales& scales, int component) const override;
  // force_limit_excess: max(|r|/μN − 1, 0); sliding_force_error: max over
  // clearly sliding samples of |r + μN sign(v)| / μN; dissipation_deficit:
  // 1 − (Σ −r v)/(Σ μN|v|) (dissipation_deficit.h).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // λ = proj_[−μN, μN](−u_free / D): stick (u_end = 0) if that fits, else
  // slide; a reversal inside the step holds the mean force
  // (reversingStepForce).
  LocalVector solveStep(const StepProblem& step) const override;
  // minmax: ρ = ω|G|; projection: ρ = 1/(ω|G|); tanh and piecewise have no
  // ρ but a slope β.
  std::shared_ptr<Law> withScaleFreeRho(const LawScales& scales) const override;
  std::optional<RhoComparison> compareRho(const LawScales& scales) const override;
  std::optional<WidthComparison> compareWidth(const LawScales& scales) const override;

  CoulombForm form() const { return form_; }
  double muN() const { return mu_n_; }
  double rho() const { return rho_; }
  double beta() const { return beta_; }

 private:
  double mu_n_;
  CoulombForm form_;
  RhoSetting rho_setting_;
  double rho_;
  bool beta_scale_free_;  // no β given: set from the scales (regularised forms)
  double beta_;
  // The scale-free width 1/β at the scales last set (withScaleFreeRho), also
  // when β is given: a regularised form cannot stick, and below this speed
  // its slip is the creep that stands for sticking, not a slip whose force
  // must reach μN (violations).
  double creep_width_;
  bool regularised() const { return form_ == CoulombForm::kTanh || form_ == CoulombForm::kPiecewise; }
};

}  // namespace eqhb
