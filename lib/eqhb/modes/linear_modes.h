// The linear modes a nonlinear mode starts from: those of the structure with
// each law replaced by its linearisation about rest, the state the mode
// approaches as its amplitude vanishes.
//
// A law component's partials at rest (x = ẋ = λ = λ̇ = 0), a = ∂Ψ/∂x,
// b = ∂Ψ/∂ẋ, c = ∂Ψ/∂λ, e = ∂Ψ/∂λ̇, give its small-amplitude behaviour:
//   c = e = 0         the DOF is held (sticking friction: Ψ = v),
//   c ≠ 0             a spring a/c and a damper b/c (λ = −(a x + b ẋ)/c),
//   c = 0, e ≠ 0      a spring b/e (elastic friction sticking: ẋ + λ̇/k_t = 0),
// each times the law's force sign. Cross-component partials are not used: a
// law whose components couple at rest is linearised component by component.
// A component between two nodes (or along a direction that is not an axis),
// reading u = w·x, adds its spring and damper as w wᵀ and, held, ties its
// nodes: w·x = 0.
// The modes are those of (K_lin, M) on the DOFs not held, under the ties,
// mass-normalised;
// the damping ratio is the modal one, ζ = φᵀ C_lin φ / (2ω), exact for
// proportional damping.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/preload/static_contact.h"

namespace eqhb {

struct LinearMode {
  double omega = 0.0;          // rad per unit time
  double damping_ratio = 0.0;  // ζ
  Eigen::VectorXd shape;       // n, φᵀ M φ = 1, zero at held DOFs
};

struct LinearisedStructure {
  Eigen::MatrixXd stiffness, damping;  // K and C with the laws' springs and dampers, n x n
  std::vector<bool> held;              // per DOF
  std::vector<Eigen::VectorXd> ties;   // w of each held component not on one DOF: w·x = 0
};

// The structure of `model` with its laws linearised about rest (above), or
// about the static state `at_rest` under a preload (each law's partials on
// its static inputs: a pressed penalty contact is its spring, a stuck
// slider its k_t).
LinearisedStructure linearisedStructure(const HbModel& model, const StaticContactState* at_rest = nullptr);

// Every mode of the linearised structure by increasing frequency (those of
// zero frequency, rigid-body motion, are left out).
std::vector<LinearMode> linearModes(const HbModel& model, const StaticContactState* at_rest = nullptr);

// The laws' forces (one per component, model.componentIndex order) that
// supply `needed`, the force the structure's dynamics asks of its laws
// (n values) on a linear motion: a component on one DOF takes what is needed
// there (the first law on a DOF; a second starts at no force); the other
// components share what remains in the least-squares sense,
// Σ sign W_lᵀ λ_l = remaining.
Eigen::VectorXd lawForcesFor(const HbModel& model, const Eigen::VectorXd& needed);

}  // namespace eqhb
