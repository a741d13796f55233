// The nonlinear mode's equations (mode_system.h) on the condensed system:
// the structure's dynamics solved exactly per harmonic, so that only the
// law forces remain unknown, as in the forced condensed system
// (hb_systems.h) but with ω and ξ among the unknowns.
//
// Unknowns z = [λ̂; ω; ξ]. In complex amplitudes X = x̂_c − i x̂_s, Λ = λ̂_c − i λ̂_s
// per harmonic k > 0, with
//   A_k(ω, ξ) = K − k²ω² M + i kω (C − ξ M),
// and S the laws' force signs, the motion of harmonic k ≠ 1 is
// X = A_k⁻¹ S Wᵀ Λ and the laws read U = W X = B_k Λ; harmonic 0 reads
// U₀ = W K⁻¹ (f₀ + S Wᵀ λ₀), f₀ the kept static loads.
//
// The fundamental is where the mode resonates: A₁ is all but singular along
// the mode (exactly so for a free, undamped one), and X = A₁⁻¹ S Wᵀ Λ would
// amplify every rounding of Λ by the inverse of the mode's damping (beam-
// damper's sliding mode: 10⁵). So the fundamental is solved bordered by the
// amplitude and phase conditions, which fix φᵀ M X₁ = a:
//   [ A₁     M φ ] [ X₁ ]   [ S Wᵀ Λ₁ ]
//   [ φᵀ M   0   ] [ μ  ] = [ a       ],
// regular wherever φ is not M-orthogonal to A₁'s near null space; μ, the
// force along M φ the motion would need beside the laws', is zero on the
// mode: Re μ = Im μ = 0 are the system's last two equations. Then
// U₁ = B₁ Λ₁ + b₁ a and μ = m₁ Λ₁ + h₁ a.
//
// The ω and ξ columns of the Jacobian come from the derivative of an
// inverse, ∂(Ā⁻¹)/∂p = −Ā⁻¹ (∂Ā/∂p) Ā⁻¹, with
//   ∂A_k/∂ω = −2k²ω M + i k (C − ξ M),   ∂A_k/∂ξ = −i kω M
// (the border does not move), the left factors from the transposed solve
// (K and C need not be symmetric). A_k changes with the unknowns ω and ξ:
// every evaluation at a new (ω, ξ) factors each A_k again (dense complex
// LU, n³/3 per harmonic), so the full system is the cheaper one for large
// structures; this one has a few law DOFs' unknowns and needs K regular.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "eqhb/harmonic_balance/law_assembly.h"
#include "eqhb/modes/full_mode_system.h"
#include "eqhb/modes/mode_system.h"

namespace eqhb {

class CondensedModeSystem : public ModeSystem {
 public:
  // As makeModeSystem (mode_system.h); also throws InputError for a model
  // without laws (nothing to condense to) or a singular K.
  CondensedModeSystem(const HbModel& model, const Eigen::VectorXd& shape, bool keep_static_loads = false);

  int size() const override { return size_; }
  int coefficientCount() const override { return coefficients_; }
  int motionCount() const override { return 0; }
  bool condensed() const override { return true; }
  // At the amplitude last set (the fundamental's border).
  Eigen::VectorXd fullCoefficients(const Eigen::VectorXd& z) const override;
  Eigen::VectorXd fromFullCoefficients(const Eigen::VectorXd& full) const override {
    return full.tail(coefficients_);
  }
  const HbModel& model() const override { return full_.model(); }
  void prepareAt(double omega) override;

  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;
  void amplitudeDerivative(Eigen::Ref<Eigen::VectorXd> column) const override { column = amplitude_column_; }
  // The full mode system's law rows; the μ rows in the law force level
  // times max |W φ|.
  void residualScales(Eigen::Ref<Eigen::VectorXd> scales) const override;
  // The full mode system's check on the recovered [x̂; λ̂; ω; ξ].
  std::string violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& z) override;

 private:
  using Complex = std::complex<double>;
  // The construction's steps: W and S Wᵀ with the fundamental's border;
  // W K⁻¹ S Wᵀ and W K⁻¹ f₀ (throws for a singular K); every buffer.
  void attachLaws();
  void condenseStaticHarmonic();
  void sizeBuffers();
  // B_k, b₁, m₁, h₁ (and with `derivatives` their ∂/∂ω, ∂/∂ξ) at (ω, ξ),
  // kept until they change. False where some A_k (or the bordered A₁) is
  // singular.
  bool receptanceAt(double omega, double xi, bool derivatives);
  // One harmonic's factors: bordered for the fundamental.
  bool factorHarmonic(size_t h, double omega, double xi, bool derivatives);
  // The laws' displacement coefficients U (nb x m) for the forces of z, and
  // with `derivatives` ∂U/∂ω, ∂U/∂ξ and ∂U/∂a.
  void readDisplacements(const Eigen::Ref<const Eigen::VectorXd>& z, bool derivatives);
  bool evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                Eigen::Ref<Eigen::MatrixXd>* jacobian);
  void lawJacobian(int l, double omega, Eigen::Ref<Eigen::MatrixXd> jacobian);
  void borderRows(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                  Eigen::Ref<Eigen::MatrixXd>* jacobian);

  mutable FullModeSystem full_;  // the model, ρ, scales and the physics check
  LawAssembly laws_;
  int n_, nb_, m_, coefficients_, size_, fundamental_ = 0;
  std::vector<int> harmonic_;                     // k per harmonic index
  std::vector<int> offset_;                       // basis offset per harmonic index
  Eigen::MatrixXd mass_, damping_, stiffness_;    // dense n x n
  Eigen::MatrixXcd reads_, loads_, reads_transpose_;  // W (m x n), S Wᵀ and Wᵀ (n x m)
  Eigen::MatrixXcd border_loads_, border_reads_rhs_;  // [S Wᵀ 0; 0 1] and [Wᵀ 0; 0 1], n+1 x m+1
  Eigen::VectorXd mass_shape_;                    // M φ
  double mode_at_laws_ = 0.0;                     // max |W φ|
  Eigen::FullPivLU<Eigen::MatrixXd> static_lu_;  // K, when the basis has harmonic 0
  Eigen::VectorXd static_load_;                   // f₀, n
  Eigen::MatrixXd static_coupling_;               // W K⁻¹ S Wᵀ, m x m
  Eigen::VectorXd static_offset_;                 // W K⁻¹ f₀, m
  // Per harmonic index with k > 0: B_k, ∂B_k/∂ω, ∂B_k/∂ξ (m x m).
  std::vector<Eigen::MatrixXcd> coupling_, coupling_omega_, coupling_xi_;
  // The fundamental's border: U₁ = B₁ Λ₁ + b₁ a, μ = m₁ Λ₁ + h₁ a, and their
  // derivatives in ω and ξ.
  Eigen::VectorXcd border_reads_, border_reads_omega_, border_reads_xi_;      // b₁
  Eigen::RowVectorXcd defect_row_, defect_row_omega_, defect_row_xi_;        // m₁
  Complex defect_gain_ = 0.0, defect_gain_omega_ = 0.0, defect_gain_xi_ = 0.0;  // h₁
  double cached_omega_ = -1.0, cached_xi_ = 0.0;
  bool cached_derivatives_ = false;
  // Scratch, sized at construction: n x n and n x m; the fundamental's
  // n+1 x n+1 and n+1 x m+1.
  Eigen::MatrixXcd a_, right_, left_, mass_right_, derivative_;
  Eigen::MatrixXcd bordered_, border_right_, border_left_, border_mass_right_, border_derivative_, border_product_;
  Eigen::PartialPivLU<Eigen::MatrixXcd> lu_, bordered_lu_;
  Eigen::MatrixXd displacements_, displacements_omega_, displacements_xi_, displacements_amplitude_;  // nb x m
  Eigen::VectorXd amplitude_column_;  // ∂g/∂a at the last Jacobian
};

}  // namespace eqhb
