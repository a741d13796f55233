// A polynomial spring, NLvib's "polynomialStiffness" on one coordinate:
// force −Σ_k c_k x^{p_k} on the structure, kept as a DAE like the cubic
// spring (cubic_stiffness.h): λ is an unknown and
//   Ψ = λ + Σ_k c_k x^{p_k} = 0.
// Plain integer powers: an even power pulls one way whatever the sign of x
// (then the law is not odd and needs every harmonic, the constant one too).
#pragma once

#include <vector>

#include "eqhb/laws/law.h"

namespace eqhb {

class PolynomialStiffness : public Law {
 public:
  // Throws InputError: as many finite coefficients as exponents, each
  // exponent an integer in [1, kMaxExponent].
  PolynomialStiffness(std::vector<double> coefficients, std::vector<int> exponents);
  static constexpr int kMaxExponent = 25;

  std::string type() const override { return "polynomial"; }
  int dimension() const override { return 1; }
  bool usesDisplacement() const override { return true; }
  bool usesVelocity() const override { return false; }
  bool oddSymmetric() const override { return odd_; }
  bool needsConstantTerm() const override { return !odd_; }
  void evaluate(LawSamples& samples, bool with_derivatives) const override;
  // dae_residual: max |λ + P(x)| / max(|λ|, the force scale).
  std::vector<std::pair<std::string, double>> violations(const LawSamples& samples,
                                                         const PhysicalScales& scales) const override;
  // Newton on λ + P(x_θ(λ)) = 0 with halved steps, x_θ the θ-point displacement.
  LocalVector solveStep(const StepProblem& step) const override;

  // P(x) = Σ c_k x^{p_k} and P'(x).
  double force(double x) const;
  double slope(double x) const;

 private:
  std::vector<double> coefficients_;
  std::vector<int> exponents_;
  bool odd_ = true;
};

}  // namespace eqhb
