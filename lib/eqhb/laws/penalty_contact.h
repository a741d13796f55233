// A penalty unilateral spring: the wall of the Signorini law (signorini.h)
// made elastic, the field's common contact model (NLvib's "unilateralSpring",
// f = k_n max(0, x − g0) on the left-hand side). Same sign convention as
// Signorini: the wall stands at x = g0 approached from below, the gap is
// g = g0 − x, the unknown λ is the pressure p, the force on the structure
// is −p, and
//   p = k_n max(0, x − g0) = k_n max(0, −g),   Ψ = p − k_n max(0, x − g0).
// Ψ is piecewise linear in x (Lipschitz), its weak derivative ∂Ψ/∂x is −k_n
// in contact and 0 apart (0 at the kink x = g0 itself, the constant branch).
// As k_n → ∞ the solutions tend to the Signorini law's.
#pragma once

#include <cmath>

#include "eqhb/laws/law.h"

namespace eqhb {

class PenaltyContact : public Law {
 public:
  // Throws InputError: k_n > 0 and g0, both finite.
  PenaltyContact(double stiffness, double gap);
  std::string type() const override { return "penalty-contact"; }
  int dimension() const override { return 1; }
  double forceSign() const override { return -1.0; }
  bool usesDisplacement() const override { return true; }
  bool usesVelocity() const override { return false; }
  std::optional<StaticStatus> staticStatus(const LawSamples& rest) const override;
  // A pressure p >= 0 that is not zero has a positive mean.
  bool needsConstantTerm() const override { return true; }
  // The wall's position is the law's length; it has no force of its own.
  double displacementLevel() const override { return std::abs(gap_); }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  // Relative to max|p| over the period (never below the problem's force
  // scale's floor): penalty_law max |p − k_n max(0, x − g0)|, and
  // negative_pressure max(−p, 0).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // p = k_n max(0, x_θ(p) − g0) at the step's θ-point, solved in closed form.
  LocalVector solveStep(const StepProblem& step) const override;
  double stiffness() const { return stiffness_; }
  double gap() const { return gap_; }

 private:
  double stiffness_, gap_;
};

}  // namespace eqhb
