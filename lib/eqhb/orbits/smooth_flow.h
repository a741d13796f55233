// Integration of a linear structure with smooth nonlinear laws, for shooting:
//   M ẍ + C ẋ + K x = f(t) + Σ forces(x, ẋ),
// cubic stiffness (force −ε x³) and planar Coulomb friction while it slides
// (force −μN v/‖v‖, smooth for v ≠ 0). A 2D contact that comes to rest
// (‖v‖ → 0, where sticking would start) is reported as a failure, not
// integrated through.
//
// The integrator is the 3-stage Gauss–Legendre collocation method (order 6,
// A-stable, symplectic), stages solved by Newton, with step-doubling error
// control (local error below kLocalTolerance of the state's scale). The
// Jacobian of each step is the exact derivative of the discrete map,
// dK = (I − h (A ⊗ J))⁻¹ J,  dy₁/dy₀ = I + h Σ b_i dK_i,
// so the monodromy matches the computed period map to round-off. Extremes of
// x_i and samples are taken by one Gauss step from the step start, as
// accurate as the steps themselves.
#pragma once

#include <memory>

#include "eqhb/orbits/piecewise_linear_flow.h"

namespace eqhb::orbits {

constexpr double kLocalTolerance = 1e-14;

class SmoothFlow : public Flow {
 public:
  // Throws InputError unless every law is cubic or Coulomb 2D.
  explicit SmoothFlow(const HbModel& model);
  static bool supports(const HbModel& model);

  int stateSize() const override { return 2 * n_; }
  double period() const override { return 2.0 * M_PI / omega_; }
  FlowResult integrate(const Eigen::VectorXd& y0, double t0, double duration, bool with_jacobian,
                       FlowSamples* samples = nullptr) const override;

 private:
  struct Site {
    bool cubic = false;
    int dof = 0, second_dof = 0;
    double coefficient = 0.0;  // ε or μN
  };
  // ẏ and, if jacobian, ∂ẏ/∂y; false where 2D friction reaches rest.
  bool field(double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy, Eigen::MatrixXd* jacobian) const;
  // One Gauss step of size h from (t, y); dy1 = ∂y1/∂y if asked.
  bool step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y1, Eigen::MatrixXd* dy1) const;
  void lawForces(const Eigen::VectorXd& y, Eigen::Ref<Eigen::VectorXd> out) const;

  int n_ = 0;
  double omega_ = 1.0, rate_ = 1.0;
  Eigen::MatrixXd mass_inverse_, damping_, stiffness_;
  std::vector<HarmonicLoad> loads_;
  std::vector<Site> sites_;
  int components_ = 0;
};

// The flow for a model's laws: piecewise linear (Coulomb 1D, Signorini) or
// smooth (cubic, sliding Coulomb 2D). Throws InputError for other laws or
// mixes.
std::unique_ptr<Flow> makeFlow(const HbModel& model, double restitution);

}  // namespace eqhb::orbits
