// A quadratic (velocity-squared) damper, the drag of a fluid film or of
// air: force −c ẋ|ẋ| on the structure, kept as a DAE like the springs:
//   Ψ = λ + c ẋ|ẋ| = 0,   ∂Ψ/∂ẋ = 2c|ẋ|.
// Over one cycle of ẋ = ωX sin ωt it dissipates (8/3) c ω² X³, the work of
// an equivalent viscous damper c_eq = 8 c ω X / (3π).
#pragma once

#include "eqhb/laws/law.h"

namespace eqhb {

class QuadraticDamping : public Law {
 public:
  explicit QuadraticDamping(double coefficient);  // finite, >= 0
  std::string type() const override { return "quadratic-damping"; }
  int dimension() const override { return 1; }
  bool usesDisplacement() const override { return false; }
  bool usesVelocity() const override { return true; }
  bool oddSymmetric() const override { return true; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  // dae_residual: max |λ + c v|v|| / max(|λ|, the force scale).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // λ = −c u|u| at the end velocity u = u_free + D λ, in closed form.
  LocalVector solveStep(const StepProblem& step) const override;
  double coefficient() const { return coefficient_; }

 private:
  double coefficient_;
};

}  // namespace eqhb
