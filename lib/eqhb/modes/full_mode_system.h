// The nonlinear mode's equations (mode_system.h) on the full system.
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
#include "eqhb/modes/mode_system.h"

namespace eqhb {

class FullModeSystem : public ModeSystem {
 public:
  // As makeModeSystem (mode_system.h); throws InputError as FullSystem does.
  FullModeSystem(const HbModel& model, const Eigen::VectorXd& shape, bool keep_static_loads = false);

  int size() const override { return size_; }
  int coefficientCount() const override { return inner_size_; }
  int motionCount() const override { return dynamic_rows_; }
  bool condensed() const override { return false; }
  Eigen::VectorXd fullCoefficients(const Eigen::VectorXd& z) const override { return z.head(inner_size_); }
  Eigen::VectorXd fromFullCoefficients(const Eigen::VectorXd& full) const override { return full; }
  const HbModel& model() const override { return inner_.model(); }
  void prepareAt(double omega) override;
  // Only the amplitude row holds a: −1 there.
  void amplitudeDerivative(Eigen::Ref<Eigen::VectorXd> column) const override {
    column.setZero();
    column[inner_size_] = -1.0;
  }

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
  Eigen::VectorXd mass_shape_;  // M φ
  SparseMatrix mass_, damping_;
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
