// The Gauss–Legendre step of SmoothFlow (smooth_flow.h): 3-stage
// collocation (order 6, A-stable), stages solved by Newton, the step's exact
// derivative dy₁/dy₀ = I + h Σ b_i dK_i with dK = (I − h (A ⊗ J))⁻¹ J; and the
// stage guess of a step from a planar slide at rest.
#include <algorithm>
#include <cmath>
#include <limits>

#include "eqhb/orbits/smooth_flow.h"

namespace eqhb::orbits {

namespace {

// Gauss–Legendre, 3 stages (Butcher tableau, order 6).
const double kR = std::sqrt(15.0);
const double kC[3] = {0.5 - kR / 10.0, 0.5, 0.5 + kR / 10.0};
const double kA[3][3] = {{5.0 / 36.0, 2.0 / 9.0 - kR / 15.0, 5.0 / 36.0 - kR / 30.0},
                         {5.0 / 36.0 + kR / 24.0, 2.0 / 9.0, 5.0 / 36.0 - kR / 24.0},
                         {5.0 / 36.0 + kR / 30.0, 2.0 / 9.0 + kR / 15.0, 5.0 / 36.0}};
const double kB[3] = {5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0};

}  // namespace

bool SmoothFlow::restartGuess(double t, const Eigen::VectorXd& y, const Modes& modes, Eigen::VectorXd& a0,
                              Eigen::VectorXd& jerk) const {
  // The planar sites at rest, held: λ and its rate.
  Modes held = modes;
  for (size_t s = 0; s < sites_.size(); ++s)
    if (sites_[s].kind == Kind::kPlanar && modes[s] == Mode::kSlide && y[n_ + sites_[s].dof] == 0.0 &&
        y[n_ + sites_[s].second_dof] == 0.0)
      held[s] = Mode::kStick;
  Eigen::VectorXd b, df, dy;
  Eigen::MatrixXd db;
  if (held == modes || !freeForce(t, y, held, b, &db)) return false;
  const Constraint& c = constraint(held);
  Eigen::VectorXd f0;
  if (!field(t, y, held, f0, nullptr)) return false;
  forcing(t, dy, &df);
  const Eigen::VectorXd lambda = c.multiplier * b, lambda_rate = c.multiplier * (df + db * f0);
  // Saturated friction μN λ̂ in place of λ: a0 = M⁻¹(b + Pᵀ μN λ̂); the
  // excess grows at d‖λ‖/dt, pushing along −λ̂.
  Eigen::VectorXd saturated = Eigen::VectorXd::Zero(n_), growth = Eigen::VectorXd::Zero(n_);
  for (size_t s = 0; s < sites_.size(); ++s) {
    if (held[s] == modes[s]) continue;
    const int row = c.first_row[s];
    const Eigen::Vector2d l = lambda.segment<2>(row);
    const double norm = l.norm();
    if (!(norm > 0.0)) return false;
    const Eigen::Vector2d unit = l / norm;
    const double rate = std::max(unit.dot(lambda_rate.segment<2>(row)), 0.0);
    saturated[sites_[s].dof] += sites_[s].coefficient * unit[0];
    saturated[sites_[s].second_dof] += sites_[s].coefficient * unit[1];
    growth[sites_[s].dof] -= rate * unit[0];
    growth[sites_[s].second_dof] -= rate * unit[1];
  }
  // The other stuck sites stay held.
  Modes others = modes;
  Eigen::VectorXd b_others;
  for (size_t s = 0; s < sites_.size(); ++s)
    if (held[s] != modes[s]) others[s] = Mode::kSmooth;  // excluded from b, its force added below
  if (!freeForce(t, y, others, b_others, nullptr)) return false;
  const Constraint& co = constraint(others);
  a0 = co.projector * (b_others + saturated);
  jerk = co.projector * growth;
  return true;
}

bool SmoothFlow::step(double t, const Eigen::VectorXd& y, double h, const Modes& modes, Eigen::VectorXd& y1,
                      Eigen::MatrixXd* dy1) const {
  const int d = 2 * n_;
  Eigen::VectorXd k(3 * d), stage(d), fi;
  Eigen::VectorXd f0;
  if (field(t, y, modes, f0, nullptr)) {
    for (int i = 0; i < 3; ++i) k.segment(i * d, d) = f0;
  } else {
    Eigen::VectorXd a0, jerk;
    if (!restartGuess(t, y, modes, a0, jerk)) return false;
    for (int i = 0; i < 3; ++i) {
      const double tau = kC[i] * h;
      k.segment(i * d, n_) = y.tail(n_) + tau * a0 + 0.5 * tau * tau * jerk;
      k.segment(i * d + n_, n_) = a0 + tau * jerk;
    }
  }
  Eigen::MatrixXd jac[3];
  Eigen::MatrixXd newton(3 * d, 3 * d);
  Eigen::VectorXd residual(3 * d);
  bool converged = false;
  for (int it = 0; it < 30; ++it) {
    for (int i = 0; i < 3; ++i) {
      stage = y;
      for (int j = 0; j < 3; ++j) stage += h * kA[i][j] * k.segment(j * d, d);
      if (!field(t + kC[i] * h, stage, modes, fi, &jac[i])) return false;
      residual.segment(i * d, d) = k.segment(i * d, d) - fi;
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) newton.block(i * d, j * d, d, d) = -h * kA[i][j] * jac[i];
    newton.diagonal().array() += 1.0;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(newton);
    const Eigen::VectorXd delta = lu.solve(residual);
    k -= delta;
    if (!k.allFinite()) return false;
    // Converged at round-off of the stage derivatives, whose scale is at
    // least the state's times the fastest rate and the accelerations the
    // loads and friction limits give (forces that cancel near rest leave
    // round-off of that size).
    const double k_scale = std::max({k.cwiseAbs().maxCoeff(), rate_ * y.cwiseAbs().maxCoeff(), acceleration_scale_});
    if (delta.cwiseAbs().maxCoeff() <= 4.0 * std::numeric_limits<double>::epsilon() * (k_scale + 1e-300)) {
      converged = true;
      if (dy1) {
        // Derivative of the converged stages (the last Newton matrix is at
        // the iterate before the final correction, which is at round-off).
        Eigen::MatrixXd rhs(3 * d, d);
        for (int i = 0; i < 3; ++i) rhs.middleRows(i * d, d) = jac[i];
        const Eigen::MatrixXd dk = lu.solve(rhs);
        *dy1 = Eigen::MatrixXd::Identity(d, d);
        for (int i = 0; i < 3; ++i) *dy1 += h * kB[i] * dk.middleRows(i * d, d);
      }
      break;
    }
  }
  if (!converged) return false;
  y1 = y;
  for (int i = 0; i < 3; ++i) y1 += h * kB[i] * k.segment(i * d, d);
  return y1.allFinite();
}

}  // namespace eqhb::orbits
