// Friction under a varying normal load with lift-off (spec §5), on a normal
// DOF n and m = 1 or 2 tangential DOFs t (DOF order [n, t...]).
//
// Components λ = (λ_n, r_t): λ_n = N0 − p is the net normal force of the
// joint on DOF n (the static preload N0 pressing toward the wall, minus the
// contact pressure p >= 0), r_t the friction force on the tangential DOFs.
// So the preload is part of the law, and λ_n = 0 when the pressure balances
// it. Gap g = g0 − x_n, a = ρg. Normal forms:
//   min:                 Ψ_n = min(a, p)
//   fischer-burmeister:  Ψ_n = a + p − sqrt(a² + p²)
//   compliant:           Ψ_n = min(ρ(g + p/k_n), p)  (elastic layer, no impact law)
// The compliant form is p = k_n max(0, −g) written as the complementarity
// 0 <= p ⊥ g + p/k_n >= 0: rows of the same scale as the min form's for any
// k_n, and the min form itself in the limit k_n → ∞ (the direct form
// p − k_n max(0, −g) has rows growing like k_n and stalls the solvers).
// Tangential (friction_kernels.h) with the varying limit L = μ max(p, 0) and
// slip velocity u = ẋ_t, or u = ẋ_t + ṙ_t/k_t when a tangential stiffness
// k_t is given (elastic dry friction in series, Jenkins, under p(t)).
// With x_n held at g0 and p ≡ N0 the tangential equations are those of
// Coulomb1D / Coulomb2D with μN = μ N0.
#pragma once

#include <optional>

#include "eqhb/laws/joints/friction_kernels.h"
#include "eqhb/laws/law.h"

namespace eqhb {

enum class NormalForm { kMin, kFischerBurmeister, kCompliant };

NormalForm parseNormalForm(const std::string& name, const std::string& field);
std::string normalFormName(NormalForm form);

struct ContactFrictionParameters {
  int tangential = 1;                           // m, 1 or 2
  double mu = 0.0;                              // >= 0
  double preload = 0.0;                         // N0 >= 0
  double gap = 0.0;                             // g0, finite
  NormalForm normal = NormalForm::kMin;
  std::optional<double> normal_stiffness;       // k_n > 0, required by (only for) compliant
  FrictionForm friction = FrictionForm::kProjection;  // minmax only with m = 1
  std::optional<double> tangential_stiffness;   // k_t > 0: elastic friction
  RhoSetting rho;                               // > 0; one value for both equations when given
};

class ContactFriction : public Law {
 public:
  // Throws InputError naming the field (mu, preload, gap, k_n, k_t, rho,
  // friction_form, tangential).
  explicit ContactFriction(const ContactFrictionParameters& parameters);
  std::string type() const override { return "contact-friction"; }
  int dimension() const override { return 1 + p_.tangential; }
  bool usesDisplacement() const override { return true; }
  bool usesVelocity() const override { return true; }
  bool rateIndependent() const override { return true; }
  std::optional<StaticStatus> staticStatus(const LawSamples& rest) const override;
  bool usesForceRate() const override { return p_.tangential_stiffness.has_value(); }
  bool needsConstantTerm() const override { return true; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  double forceLevel() const override;
  double displacementLevel() const override;
  double residualScale(const PhysicalScales& scales, int component) const override;
  // Relative measures (0 when the law holds): negative_pressure max(−p)/max p,
  // penetration max(−g)/max|g| (rigid forms), complementarity max|g p|/(max|g| max p)
  // (rigid forms) or compliance_error max|p − k_n max(0, −g)|/max p (compliant),
  // force_limit_excess max(‖r_t‖ − μ max(p, 0))/(μ max p), sliding_force_error
  // max ‖r_t + μ p u/‖u‖‖/(μ max p) over samples clearly sliding and pressed,
  // dissipation_deficit 1 − (Σ −r_t·u)/(Σ μ max(p, 0)‖u‖) (dissipation_deficit.h).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // Normal (Moreau's velocity-level contact with Newton's impact law, or the
  // implicit elastic layer) and tangential (maximal dissipation on the disc
  // of radius μp, with the slider of k_t) solved alternately to round-off.
  LocalVector solveStep(const StepProblem& step) const override;

  // Scale-free: the normal ρ compares a gap with a pressure, 1/(|G| + 1/k_n);
  // the friction ρ follows its form with the slip mobility ω(|G| + 1/k_t).
  std::shared_ptr<Law> withScaleFreeRho(const LawScales& scales) const override;
  std::optional<RhoComparison> compareRho(const LawScales& scales) const override;

  const ContactFrictionParameters& parameters() const { return p_; }

 private:
  ContactFrictionParameters p_;
  double normal_rho_, friction_rho_;  // both p_.rho unless scale-free
  double compliance_ = 0.0;  // 1/k_t, 0 when rigid
};

}  // namespace eqhb
