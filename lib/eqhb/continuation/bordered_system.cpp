#include "eqhb/continuation/bordered_system.h"

#include <algorithm>
#include <cmath>
#include <exception>

namespace eqhb {

ArcScales ArcScales::at(const Eigen::VectorXd& z, double floor, double omega_scale) {
  ArcScales s;
  s.z = std::max(z.norm(), floor);
  s.omega = omega_scale;
  return s;
}

Eigen::VectorXd ArcScales::scaled(const Eigen::VectorXd& zv, double omega_value) const {
  Eigen::VectorXd y(zv.size() + 1);
  y << zv / z, omega_value / omega;
  return y;
}

Eigen::VectorXd ArcScales::scaledDirection(const Eigen::VectorXd& physical) const {
  const Eigen::Index n = physical.size() - 1;
  Eigen::VectorXd t(n + 1);
  t << physical.head(n) / z, physical[n] / omega;
  return t.normalized();
}

Eigen::VectorXd ArcScales::physicalDirection(const Eigen::VectorXd& scaled_direction) const {
  const Eigen::Index n = scaled_direction.size() - 1;
  Eigen::VectorXd d(n + 1);
  d << scaled_direction.head(n) * z, scaled_direction[n] * omega;
  return d;
}

BorderedSystem::BorderedSystem(HbSystem& inner, const ArcScales& scales)
    : inner_(inner), n_(inner.size()), scales_(scales), current_(inner.omega()), g_(n_), g_shift_(n_) {}

void BorderedSystem::setConstraint(const Eigen::VectorXd& tangent, const Eigen::VectorXd& predicted) {
  tangent_ = tangent;
  predicted_ = predicted;
}

bool BorderedSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> out) {
  if (!moveTo(y[n_] * scales_.omega)) return false;
  if (!inner_.residual(y.head(n_) * scales_.z, out.head(n_))) return false;
  out[n_] = tangent_.dot(y - predicted_);
  return true;
}

bool BorderedSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> out,
                                         Eigen::Ref<Eigen::MatrixXd> j) {
  const double omega = y[n_] * scales_.omega;
  const Eigen::VectorXd z = y.head(n_) * scales_.z;
  // ∂g/∂ω by a forward difference (the law projection depends on ω
  // through the velocity, the condensation through every A_k).
  const double delta = 1e-7 * std::max(1.0, std::abs(omega));
  if (!moveTo(omega + delta) || !inner_.residual(z, g_shift_)) return false;
  // J_z straight into its block (no n x n copy: 92 MB at 3400 unknowns).
  if (!moveTo(omega) || !inner_.residualAndJacobian(z, g_, j.topLeftCorner(n_, n_))) return false;
  out.head(n_) = g_;
  out[n_] = tangent_.dot(y - predicted_);
  j.topLeftCorner(n_, n_) *= scales_.z;
  j.topRightCorner(n_, 1) = (g_shift_ - g_) / delta * scales_.omega;
  j.bottomRows(1) = tangent_.transpose();
  return true;
}

void BorderedSystem::residualScales(Eigen::Ref<Eigen::VectorXd> scales) const {
  inner_.residualScales(scales.head(n_));
  scales[n_] = 1.0;
}

bool BorderedSystem::moveTo(double omega) {
  if (omega == current_) return true;
  if (!(omega > 0.0)) return false;
  try {
    inner_.setOmega(omega);
  } catch (const std::exception&) {
    return false;
  }
  current_ = omega;
  return true;
}

// The bordered Jacobian's solve for the tangent: a partial-pivoting LU
// (blocked, at matrix-product speed), in place, where its condition
// estimate, rows equilibrated, shows the matrix far from singular; else
// (an estimate below kFastTangentRcond) the full-pivoting LU that decides
// whether it is singular (rank-revealing, but unblocked: on the lap joint at
// H = 40, 3403 unknowns, it took 74 % of an arclength sweep). Below
// kFastTangentFromUnknowns the full-pivoting LU costs little (20 ms at 500)
// and stays: its tangent, where the curve kinks, is the one the small
// scenes' sweeps were tuned on (a tangent that differs by round-off there
// can send a sweep another way: stribeck at H = 40, N = 1024).
constexpr double kFastTangentRcond = 1e-8;
constexpr int kFastTangentFromUnknowns = 512;

bool tangentAt(HbSystem& system, const ArcScales& scales, const Eigen::VectorXd& y, const Eigen::VectorXd& previous,
               Eigen::VectorXd* tangent) {
  const int n = system.size();
  BorderedSystem bordered(system, scales);
  bordered.setConstraint(previous, y);
  Eigen::VectorXd out(n + 1);
  Eigen::MatrixXd j(n + 1, n + 1);
  if (!bordered.residualAndJacobian(y, out, j)) return false;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
  rhs[n] = 1.0;
  Eigen::VectorXd t;
  // Rows scaled to unit largest entry: the solution's direction (the
  // right-hand side a multiple of e_n) is the same, and the condition
  // estimate no longer reflects the equations' units.
  const Eigen::VectorXd row_max = j.cwiseAbs().rowwise().maxCoeff();
  bool fast = n + 1 >= kFastTangentFromUnknowns && row_max.allFinite() && (row_max.array() > 0.0).all();
  if (fast) {
    j.array().colwise() /= row_max.array();
    const Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(j);
    fast = lu.rcond() > kFastTangentRcond;
    if (fast) t = lu.solve(rhs / row_max[n]);
  }
  if (!fast) {
    // j as evaluated (an LU above overwrote it).
    if (n + 1 >= kFastTangentFromUnknowns && !bordered.residualAndJacobian(y, out, j)) return false;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(j);
    if (!lu.isInvertible()) return false;
    t = lu.solve(rhs);
  }
  if (!t.allFinite() || t.norm() == 0.0) return false;
  t.normalize();
  if (t.dot(previous) < 0.0) t = -t;
  *tangent = t;
  return true;
}

}  // namespace eqhb
