#pragma once

#include <Eigen/Dense>
#include <complex>

namespace eqhb {

// exp(A τ) Φ for one constant generator A at many τ, as a monodromy's phase
// generators repeat from phase to phase and from point to point along a
// curve. A = V D V⁻¹ once (real form: D block diagonal, 2x2 blocks
// [a b; −b a] for a ± ib), then exp(A τ) Φ = V (exp(D τ) (V⁻¹ Φ)): two
// products and an O(d²) scaling instead of a scaling-and-squaring
// exponential (tens of products when ‖A τ‖ is large). Where V is
// ill-conditioned or defective (a rigid-body Jordan block, repeated
// eigenvalues) that would lose digits, so the generator keeps Eigen's
// exponential. The modes are ordered by decreasing decay rate's opposite
// (real part, largest first), so that the modes a phase of length τ leaves
// above a negligible size are a leading set (survivingModes).
class PhaseExponential {
 public:
  PhaseExponential() = default;  // of the empty generator
  explicit PhaseExponential(const Eigen::MatrixXd& generator);
  // True when exp(A τ) is formed from the eigendecomposition.
  bool decomposed() const { return decomposed_; }
  // Φ ← exp(A τ) Φ. `scratch` is reused storage of Φ's size.
  void apply(double tau, Eigen::MatrixXd& phi, Eigen::MatrixXd& scratch) const;
  // exp(A τ) itself (by the same route as apply).
  Eigen::MatrixXd exponential(double tau) const;
  // The decomposition (decomposed() only): V, V⁻¹, and ψ ← exp(D τ) ψ on
  // rows in V's coordinates, so that exp(A τ) Φ = V exp(D τ) V⁻¹ Φ. ψ may
  // hold the leading modes only (its rows: the first of V's columns).
  const Eigen::MatrixXd& vectors() const { return vectors_; }
  const Eigen::MatrixXd& inverse() const { return inverse_; }
  void scaleModes(double tau, Eigen::Ref<Eigen::MatrixXd> psi) const;
  // The number of leading modes whose growth over τ, e^{Re λ τ}, is above
  // kNegligibleGrowth (a 2x2 block's pair together); the others are taken
  // as gone after the phase (decomposed() only).
  Eigen::Index survivingModes(double tau) const;
  // exp(λ τ) per eigenvalue λ of A (decomposed() only): the multipliers
  // of a phase that lasts the whole period.
  void multipliers(double tau, Eigen::Ref<Eigen::VectorXcd> out) const;

  // A mode that decays below this over a phase contributes to the product
  // some 1e-14 of what the rounding of a double already does: the heavily
  // damped stiff modes of a jointed structure (the lap joint's contact
  // modes, e^{-2000} a period) are dropped rather than carried.
  static constexpr double kNegligibleGrowth = 1e-30;

  // Reciprocal condition number of V below which the decomposition is not
  // used: its error in exp(A τ) is about eps/rcond relative (2e-8 here).
  // The lap joint's scaled generators (rcond ~6e-7 after column scaling)
  // are decomposed: along its 101-point curve the radii move by at most
  // 1.2e-7 against Eigen's exponential, the verdicts are the same, and the
  // stability takes 2.5 times less time.
  static constexpr double kMinimumRcond = 1e-8;
  // Up to this size apply() multiplies without the blocked product.
  static constexpr Eigen::Index kLazyProductSize = 24;

 private:
  double reproductionError(const Eigen::MatrixXd& generator, const Eigen::MatrixXd& v) const;

  Eigen::MatrixXd generator_;
  bool decomposed_ = false;
  Eigen::MatrixXd vectors_, inverse_;
  Eigen::VectorXd real_, imaginary_;  // per column of V; imaginary_ > 0 opens a 2x2 block
};

}  // namespace eqhb
