// The extended periodic motion concept (EPMC; Krack 2015, "Nonlinear modal
// analysis of nonconservative systems", as in NLvib): the nonlinear mode at
// modal amplitude a is the periodic motion of the unforced structure with an
// added negative mass-proportional damping −ξ M ẋ,
//
//   M ẍ + (C − ξ M) ẋ + K x = Σ_laws W_l λ_l,   Ψ_l(x, ẋ, λ_l) = 0,
//
// which feeds back exactly the energy the structure and its laws dissipate
// over a cycle; the mode's damping ratio is ζ = ξ / (2ω). Two more equations
// fix the amplitude and the phase:
//   amplitude   φᵀ M x̂₁,c − a = 0,
//   phase       φᵀ M x̂₁,s     = 0,
// the mass-weighted projection of the fundamental (cos, sin) onto the linear
// mode φ (mass-normalised) it started from.
//
// ModeSystem is what the backbone's tracers (path_tracer.h,
// sliding_branch.h) solve: unknowns z = [coefficients; ω; ξ], on the full
// system (full_mode_system.h: the coefficients are [x̂; λ̂]) or on the
// condensed one (condensed_mode_system.h: λ̂ alone, x̂ = A_k(ω, ξ)⁻¹ W λ̂).
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/solvers/square_system.h"

namespace eqhb {

class ModeSystem : public SquareSystem {
 public:
  // The coefficients come first in z, then ω and ξ.
  virtual int coefficientCount() const = 0;
  int omegaIndex() const { return coefficientCount(); }
  int xiIndex() const { return coefficientCount() + 1; }
  // The leading coefficients that measure the motion, the displacements (the
  // condensed system has none), which weigh in a continuation step
  // (mode_path_system.h).
  virtual int motionCount() const = 0;
  virtual bool condensed() const = 0;

  // The full coefficients [x̂; λ̂] of a solution vector z.
  virtual Eigen::VectorXd fullCoefficients(const Eigen::VectorXd& z) const = 0;
  // The coefficients of this system for full ones (the tail of a z).
  virtual Eigen::VectorXd fromFullCoefficients(const Eigen::VectorXd& full) const = 0;
  // z of this system for the full system's [x̂; λ̂; ω; ξ].
  Eigen::VectorXd fromFullPoint(const Eigen::VectorXd& full_point) const;

  // The model the system solves (no loads but the kept static ones, ρ as
  // set by prepareAt).
  virtual const HbModel& model() const = 0;
  const Eigen::VectorXd& shape() const { return shape_; }
  double amplitude() const { return amplitude_; }
  void setAmplitude(double amplitude) { amplitude_ = amplitude; }
  // Sets every scale-free ρ for frequency ω and holds it during the solves
  // that follow. For the exact law ρ changes the residual, not its zeros; the
  // truncated series' zeros move with it a little (beam-damper's first fold:
  // ω 28.96, 29.37, 29.65 at ρ 1, 10, 100).
  virtual void prepareAt(double omega) = 0;
  // ∂g/∂a at the last residualAndJacobian (size() values): how the
  // equations move with the amplitude, for continuation in log a
  // (mode_path_system.h).
  virtual void amplitudeDerivative(Eigen::Ref<Eigen::VectorXd> column) const = 0;

 protected:
  explicit ModeSystem(const Eigen::VectorXd& shape) : shape_(shape) {}
  Eigen::VectorXd shape_;  // φ, φᵀ M φ = 1
  double amplitude_ = 1.0;
};

// `model`: the scene's (its loads are ignored, but for the constant ones
// when `keep_static_loads`: a preload the mode vibrates about); `shape`: φ,
// n values with φᵀ M φ = 1. Throws InputError for an invalid model, a basis
// without the fundamental or a structure that does not fit.
std::unique_ptr<ModeSystem> makeModeSystem(const HbModel& model, const Eigen::VectorXd& shape,
                                           bool keep_static_loads, bool condensed);

}  // namespace eqhb
