// Pseudo-arclength pieces shared by the arclength sweep: the scaled
// coordinates ŷ = (z / s_z, ω / s_ω), the system g(z, ω) = 0 bordered by the
// arclength condition, and the unit tangent of the curve at a point.
#pragma once

#include <Eigen/Dense>

#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/solvers/square_system.h"

namespace eqhb {

// Scales of the unknowns: one for every component of z, their running
// magnitude ‖z‖, so that a unit of arclength is a change of the response
// by its own size however large it grows (with the RMS instead, a unit
// step would be a change by 1/√n of it: steps shrink with the number of
// unknowns); and one for ω, the width of the range.
struct ArcScales {
  double z = 1.0, omega = 1.0;
  // s_z = max(‖z‖, floor): the floor keeps the scale away from zero where
  // the response passes near rest.
  static ArcScales at(const Eigen::VectorXd& z, double floor, double omega_scale);
  Eigen::VectorXd scaled(const Eigen::VectorXd& z, double omega) const;
  // A direction (dz, dω) in physical units as a unit vector in these scales:
  // the tangent stays the same geometric direction when the scales change.
  Eigen::VectorXd scaledDirection(const Eigen::VectorXd& physical) const;
  Eigen::VectorXd physicalDirection(const Eigen::VectorXd& scaled) const;
};

// [g(z, ω); τᵀ(ŷ − ŷ_pred)] = 0 in the scaled unknowns ŷ.
class BorderedSystem : public SquareSystem {
 public:
  BorderedSystem(HbSystem& inner, const ArcScales& scales);
  int size() const override { return n_ + 1; }
  void setConstraint(const Eigen::VectorXd& tangent, const Eigen::VectorXd& predicted);
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> out) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> out,
                           Eigen::Ref<Eigen::MatrixXd> j) override;
  // The inner equations in their own scales; the arclength row is scaled already.
  void residualScales(Eigen::Ref<Eigen::VectorXd> scales) const override;

 private:
  bool moveTo(double omega);
  HbSystem& inner_;
  int n_;
  ArcScales scales_;
  double current_;
  Eigen::VectorXd tangent_, predicted_, g_, g_shift_;
};

// The unit tangent (scaled) at ŷ: the null direction of [J_z s_z, J_ω s_ω],
// bordered by `previous` and oriented along it. False where the bordered
// Jacobian is singular or the evaluation fails.
bool tangentAt(HbSystem& system, const ArcScales& scales, const Eigen::VectorXd& y, const Eigen::VectorXd& previous,
               Eigen::VectorXd* tangent);

}  // namespace eqhb
