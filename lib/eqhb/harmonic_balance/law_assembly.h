// The numerical Galerkin projection of the laws (spec §3), shared by the full
// and the condensed systems: coefficients of x and λ at a law's DOFs ->
// samples -> Ψ and its weak partials -> projected residual and Jacobian
// blocks J = Q diag(∂Ψ/∂q) P (chained through Dω for the velocity).
//
// Callers fill displacement(l) and force(l) (nb x d, one column per
// component), call evaluate(l, ...), then read residual(l) and the blocks.
// All buffers are sized at construction; evaluate allocates nothing. When
// every law is odd and the basis has odd harmonics only, the laws are
// evaluated on the first half of the period (FourierTransform's half-wave
// sampling): the same projections for half the samples.
//
// A history law (Law::historyTerms() > 0, the alternating frequency–time
// forms) adds to the diagonal part Q diag(∂Ψ/∂x) P its terms across samples,
// Q H P with H sparse (K entries per row): the rows of P gathered into
// history_rows_ (N x nb), then Q times them, from the explicit Q and P made
// once at construction when some law needs them.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <utility>
#include <vector>

#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb {

class LawAssembly {
 public:
  explicit LawAssembly(const HbModel& model);

  int lawCount() const { return static_cast<int>(laws_.size()); }
  int dimension(int l) const { return laws_[l].law->dimension(); }
  const AttachedLaw& law(int l) const { return laws_[l]; }
  // The same laws on the same DOFs with other parameters (a scale-free ρ set
  // for a new ω): the buffers stay as they are.
  void replaceLaws(const std::vector<AttachedLaw>& laws);
  FourierTransform& transform() { return transform_; }

  Eigen::MatrixXd& displacement(int l) { return slots_[l].displacement_coefficients; }
  Eigen::MatrixXd& force(int l) { return slots_[l].force_coefficients; }

  // Returns false if Ψ is not finite at some sample.
  bool evaluate(int l, double omega, bool with_jacobian);

  const Eigen::MatrixXd& residual(int l) const { return slots_[l].psi_coefficients; }
  // The law's own checks (Law::violations) on the samples of its last
  // evaluate(): the model's samples, or the first half-period of them.
  std::vector<std::pair<std::string, double>> violations(int l, const PhysicalScales& scales) const {
    return laws_[l].law->violations(slots_[l].samples, scales);
  }
  // ∂(projected Ψ_a)/∂(coefficients of x at DOF b), velocity included.
  const Eigen::MatrixXd& displacementBlock(int l, int a, int b) const {
    return slots_[l].displacement_blocks[a * dimension(l) + b];
  }
  // ∂(projected Ψ_a)/∂(coefficients of λ_b).
  const Eigen::MatrixXd& forceBlock(int l, int a, int b) const {
    return slots_[l].force_blocks[a * dimension(l) + b];
  }
  // ∂(projected Ψ)/∂ω (nb x d) on the samples of the last evaluate(l, omega,
  // true): Ψ sees ω only through ẋ = ω D x and λ̇ = ω D λ, so
  //   ∂Ψ_a/∂ω = Σ_b (∂Ψ_a/∂ẋ_b ẋ_b + ∂Ψ_a/∂λ̇_b λ̇_b) / ω,
  // projected like Ψ. For systems whose ω is an unknown (nonlinear modes).
  const Eigen::MatrixXd& omegaDerivative(int l, double omega);

 private:
  struct Slot {
    Eigen::MatrixXd displacement_coefficients, force_coefficients, psi_coefficients;
    Eigen::MatrixXd omega_coefficients;    // nb x d: omegaDerivative
    Eigen::MatrixXd derived_coefficients;  // nb x 2d: velocity and λ̇ of each component
    LawSamples samples;
    std::vector<Eigen::MatrixXd> displacement_blocks, force_blocks;
  };
  std::vector<AttachedLaw> laws_;
  FourierTransform transform_;
  std::vector<Slot> slots_;
  // Q H P of a history law's terms (columns ab K .. ab K + K − 1) into block.
  void addHistoryBlock(const LawSamples& samples, int first_term, int terms, Eigen::MatrixXd& block);
  Eigen::MatrixXd gram_scratch_, velocity_scratch_;
  // History laws only (else empty): P (N x nb), Q (nb x N), the period's mean
  // of each basis function, and the gathered rows H P.
  Eigen::MatrixXd synthesis_, projection_, history_rows_;
  Eigen::RowVectorXd basis_mean_;
  Eigen::VectorXd sample_scratch_;  // one channel's samples: omegaDerivative
  std::vector<std::pair<const double*, double*>> channels_;  // (coefficients, samples) to synthesise
};

}  // namespace eqhb
