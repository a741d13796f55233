// The linear dynamics both exact flows (piecewise_linear_flow.h,
// smooth_flow.h) are built on: M⁻¹ of a positive definite mass, the
// acceleration of the structure with some DOFs held, and the fastest rate of
// the model, which sets their time steps.
//
// With G the held DOFs, P their selection and b the forces other than the
// constraint forces,
//   a = Q b,  Q = M⁻¹ − M⁻¹Pᵀ(P M⁻¹Pᵀ)⁻¹P M⁻¹,  λ_G = −(P M⁻¹Pᵀ)⁻¹P M⁻¹ b.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "eqhb/laws/grounded_laws.h"
#include "eqhb/laws/law.h"
#include "eqhb/structures/linear_structure.h"

namespace eqhb::orbits {

// M⁻¹; throws InputError (structure.mass) unless M is positive definite:
// massless DOFs would make the phases differential-algebraic.
Eigen::MatrixXd invertPositiveDefiniteMass(const LinearStructure& structure);

// The structure's M⁻¹, C and K dense, as the exact flows and the monodromy
// integrate them.
struct DenseDynamics {
  DenseDynamics() = default;
  // Throws InputError (structure.mass) unless M is positive definite.
  explicit DenseDynamics(const LinearStructure& structure)
      : mass_inverse(invertPositiveDefiniteMass(structure)), damping(structure.damping),
        stiffness(structure.stiffness) {}
  Eigen::MatrixXd mass_inverse, damping, stiffness;
};

struct HeldDofs {
  Eigen::MatrixXd projector;   // Q (M⁻¹ when nothing is held)
  Eigen::MatrixXd multiplier;  // λ_G = multiplier · b, rows in the order of `dofs`
};
HeldDofs holdDofs(const Eigen::MatrixXd& mass_inverse, const std::vector<int>& dofs);


// max(√‖M⁻¹K‖∞, ‖M⁻¹C‖∞, k ω for each forcing harmonic k, ω).
double fastestRate(const Eigen::MatrixXd& mass_inverse, const Eigen::MatrixXd& stiffness,
                   const Eigen::MatrixXd& damping, const std::vector<int>& harmonics, double omega);

}  // namespace eqhb::orbits
