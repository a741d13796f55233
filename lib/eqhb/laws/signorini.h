// Signorini unilateral contact with a wall at x = g0 approached from below
// (spec §2): gap g = g0 − x >= 0, pressure p >= 0 (the unknown λ), force on
// the structure −p, complementarity 0 <= g ⊥ p >= 0, as equalities (a = ρg):
//   min:                 Ψ = min(a, p)
//   fischer-burmeister:  Ψ = a + p − sqrt(a² + p²)
//   sign-square:         Ψ = −(a − p)² + |a| a + |p| p      (the seed's form)
// Ties: min takes the p branch; Fischer–Burmeister at (0, 0) uses the
// derivative along a = p.
#pragma once

#include <cmath>

#include "eqhb/laws/law.h"

namespace eqhb {

enum class SignoriniForm { kMin, kFischerBurmeister, kSignSquare };

SignoriniForm parseSignoriniForm(const std::string& name);
std::string signoriniFormName(SignoriniForm form);

class Signorini : public Law {
 public:
  // Throws InputError: g0 finite, ρ > 0 finite.
  Signorini(double gap, SignoriniForm form, RhoSetting rho = {});
  std::string type() const override { return "signorini"; }
  int dimension() const override { return 1; }
  double forceSign() const override { return -1.0; }
  bool usesDisplacement() const override { return true; }
  bool usesVelocity() const override { return false; }
  std::optional<StaticStatus> staticStatus(const LawSamples& rest) const override;
  bool needsConstantTerm() const override { return true; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  double displacementLevel() const override { return std::abs(gap_); }
  double residualScale(const PhysicalScales& scales, int component) const override;
  // Relative to max|g| and max|p| over the period: penetration max(−g, 0),
  // negative_pressure max(−p, 0), complementarity max |g p| (0 when g ⊥ p).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // Moreau's velocity-level contact with Newton's impact law: when the gap
  // predicted at mid-step is closed, 0 <= ġ_end + e ġ_start ⊥ p >= 0.
  LocalVector solveStep(const StepProblem& step) const override;
  // ρ compares a gap with a pressure: ρ = 1/|G|.
  std::shared_ptr<Law> withScaleFreeRho(const LawScales& scales) const override;
  std::optional<RhoComparison> compareRho(const LawScales& scales) const override;
  double gap() const { return gap_; }
  double rho() const { return rho_; }

 private:
  double gap_;
  SignoriniForm form_;
  RhoSetting rho_setting_;
  double rho_;
};

}  // namespace eqhb
