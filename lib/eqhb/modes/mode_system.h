// The extended periodic motion concept (EPMC; Krack 2015, "Nonlinear modal
// analysis of nonconservative systems", as in NLvib): the nonlinear mode at
// modal amplitude a is the periodic motion of the unforced structure with an
// added negative mass-proportional damping −ξ M ẋ,
//
//   M ẍ + (C − ξ M) ẋ + K x = Σ_laws W_l λ_l,   Ψ_l(x, ẋ, λ_l) = 0,
//
// which feeds back exactly the energy the structure and its laws dissipate
// over a cycle; the mode's damping ratio is ζ = ξ / (2ω).
//
// Unknowns z = [x̂; λ̂; ω; ξ] (the full system's Fourier coefficients, then ω
// and ξ); equations = the full harmonic-balance residual (hb_systems.h)
// without loads, with A_k built on C − ξ M, then two more:
//   amplitude   φᵀ M x̂₁,c − a = 0,
//   phase       φᵀ M x̂₁,s     = 0,
// the mass-weighted projection of the fundamental (cos, sin) onto the linear
// mode φ (mass-normalised) it started from. The Jacobian is analytic, ω and
// ξ columns included (the law rows' ω column from LawAssembly::omegaDerivative),
// and assembled sparse on a pattern fixed at construction.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

class ModeSystem : public SquareSystem {
 public:
  // `model`: the scene's (its loads are ignored, but for the constant ones
  // when `keep_static_loads`: a preload the mode vibrates about); `shape`:
  // φ, n values with φᵀ M φ = 1. Throws InputError as FullSystem does, and
  // for a basis without the fundamental.
  ModeSystem(const HbModel& model, const Eigen::VectorXd& shape, bool keep_static_loads = false);

  int size() const override { return size_; }
  int omegaIndex() const { return inner_size_; }
  int xiIndex() const { return inner_size_ + 1; }
  // The full coefficients [x̂; λ̂] of a solution vector.
  Eigen::VectorXd fullCoefficients(const Eigen::VectorXd& z) const { return z.head(inner_size_); }
  // The model the system solves (no loads, ρ as set by prepareAt).
  const HbModel& model() const { return inner_.model(); }
  const Eigen::VectorXd& shape() const { return shape_; }

  double amplitude() const { return amplitude_; }
  void setAmplitude(double amplitude) { amplitude_ = amplitude; }
  // Sets every scale-free ρ for frequency ω and holds it during the solves
  // that follow. For the exact law ρ changes the residual, not its zeros; the
  // truncated series' zeros move with it a little (beam-damper's first fold:
  // ω 28.96, 29.37, 29.65 at ρ 1, 10, 100).
  void prepareAt(double omega);

  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;
  bool nativeSparseJacobian() const override { return true; }
  const SparseMatrix& jacobianPattern() override { return pattern_; }
  bool residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                                 SparseMatrix& jacobian) override;
  // Dynamics rows: the larger of the laws' force level and the structure's
  // stiffness times the mode's displacement a max|φ|; law rows: each law's
  // scale in those units; amplitude and phase rows: a.
  void residualScales(Eigen::Ref<Eigen::VectorXd> scales) const override;
  std::string violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& z) override;

 private:
  bool moveTo(double omega);
  bool evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g, double* values);
  void buildPattern();
  FullSystem inner_;
  Eigen::VectorXd shape_, mass_shape_;  // φ and M φ
  SparseMatrix mass_, damping_;
  double amplitude_ = 1.0;
  int n_, nb_, dynamic_rows_, inner_size_, size_, fundamental_;  // fundamental_: offset of harmonic 1
  std::vector<int> harmonic_of_offset_;  // k of each basis function
  SparseMatrix pattern_, inner_jacobian_;
  std::vector<int> inner_slot_;           // outer slot of each inner Jacobian value
  std::vector<int> xi_slot_;              // per mass entry and harmonic k > 0: (cos row, sin col), (sin row, cos col)
  std::vector<double> xi_factor_;         // k M_ij and −k M_ij for them (times ξω)
  int omega_column_, xi_column_;          // first slot of the ω and ξ columns
  std::vector<int> amplitude_slot_, phase_slot_;  // per DOF
  Eigen::MatrixXd mass_x_, damping_x_;    // nb x n: rows t of M X and C X
  Eigen::VectorXd omega_derivative_, values_;
};

}  // namespace eqhb
