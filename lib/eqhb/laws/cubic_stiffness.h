// Cubic stiffness kept as a DAE on purpose (spec §2): the force f_nl on the
// structure is an unknown and Ψ = f_nl + ε x³ = 0 (smooth). Its solutions
// must agree with the classical explicit substitution f_nl = −ε x³.
#pragma once

#include "eqhb/laws/law.h"

namespace eqhb {

class CubicStiffness : public Law {
 public:
  explicit CubicStiffness(double epsilon);  // finite
  std::string type() const override { return "cubic"; }
  int dimension() const override { return 1; }
  bool usesDisplacement() const override { return true; }
  bool usesVelocity() const override { return false; }
  bool oddSymmetric() const override { return true; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  // dae_residual: max |f_nl + ε x³| / max(|f_nl|, tiny).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // Newton on λ + ε x_θ(λ)³ = 0, x_θ the displacement at the θ-point.
  LocalVector solveStep(const StepProblem& step) const override;
  double epsilon() const { return epsilon_; }

 private:
  double epsilon_;
};

}  // namespace eqhb
