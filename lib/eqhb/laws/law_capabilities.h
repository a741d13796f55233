// Optional capabilities of a law, which callers query through the registry
// (law_registry.h) instead of asking for its concrete type: what the exact
// integrators of orbits/ need to know of a law they can integrate in closed
// form or by smooth phases.
#pragma once

#include <functional>

namespace eqhb {

// A law that SmoothFlow (orbits/smooth_flow.h) integrates by smooth phases
// with stick/slip events: a cubic spring, a smooth force of x and ẋ on one
// DOF, a planar Coulomb slider on two DOFs, or a Stribeck (or Coulomb: no
// drop) slider on one DOF.
struct SmoothFlowSite {
  enum class Kind { kCubic, kForce, kPlanar, kStribeck };
  Kind kind = Kind::kCubic;
  double coefficient = 0.0;  // ε (cubic), μN (planar), μ_d N (Stribeck)
  double drop = 0.0;         // Stribeck: (μ_s − μ_d) N
  double v_s = 1.0;          // Stribeck: the decay velocity
  // kForce: the force f(x, ẋ) on the structure and its partials (a
  // polynomial spring, a quadratic damper).
  std::function<void(double x, double v, double* f, double* df_dx, double* df_dv)> force;
};

// A law on one DOF that PiecewiseLinearFlow (orbits/piecewise_linear_flow.h)
// integrates in closed form between events: a Coulomb slider with limit μN
// (optionally behind a spring k_t, Jenkins), or a wall at x = g0, rigid
// (Signorini) or elastic (a penalty spring k_n pressed beyond it).
struct PiecewiseLinearSite {
  bool contact = false;
  double limit = 0.0;      // μN (friction)
  double gap = 0.0;        // g0 (contact)
  double stiffness = 0.0;  // k_t of an elastic slider (Jenkins); 0: rigid
  double penalty = 0.0;    // k_n of an elastic wall (contact); 0: rigid
  bool rigidWall() const { return contact && penalty == 0.0; }
};

}  // namespace eqhb
