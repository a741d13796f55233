#include "eqhb/orbits/smooth_flow.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "eqhb/error.h"
#include "eqhb/laws/coulomb_2d.h"
#include "eqhb/laws/cubic_stiffness.h"

namespace eqhb::orbits {

namespace {

// Gauss–Legendre, 3 stages (Butcher tableau, order 6).
const double kR = std::sqrt(15.0);
const double kC[3] = {0.5 - kR / 10.0, 0.5, 0.5 + kR / 10.0};
const double kA[3][3] = {{5.0 / 36.0, 2.0 / 9.0 - kR / 15.0, 5.0 / 36.0 - kR / 30.0},
                         {5.0 / 36.0 + kR / 24.0, 2.0 / 9.0, 5.0 / 36.0 - kR / 24.0},
                         {5.0 / 36.0 + kR / 30.0, 2.0 / 9.0 + kR / 15.0, 5.0 / 36.0}};
const double kB[3] = {5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0};
constexpr int kMaxSteps = 2000000;

}  // namespace

bool SmoothFlow::supports(const HbModel& model) {
  if (model.laws.empty()) return false;
  for (const auto& attached : model.laws)
    if (!dynamic_cast<const CubicStiffness*>(attached.law.get()) && !dynamic_cast<const Coulomb2D*>(attached.law.get()))
      return false;
  return true;
}

std::unique_ptr<Flow> makeFlow(const HbModel& model, double restitution) {
  if (!(restitution >= 0.0 && restitution <= 1.0))
    throwInputError("restitution", formatNumber(restitution), "must be in [0, 1]");
  if (SmoothFlow::supports(model)) return std::make_unique<SmoothFlow>(model);
  return std::make_unique<PiecewiseLinearFlow>(model, restitution);
}

SmoothFlow::SmoothFlow(const HbModel& model) {
  model.validate();
  const LinearStructure& s = model.structure;
  n_ = s.dofs();
  omega_ = model.omega;
  const Eigen::LLT<Eigen::MatrixXd> mass_factor{Eigen::MatrixXd(s.mass)};
  if (mass_factor.info() != Eigen::Success || mass_factor.matrixL().toDenseMatrix().diagonal().minCoeff() <= 0.0)
    throwInputError("structure.mass", "singular", "exact orbits need a positive definite mass (no massless DOFs)");
  mass_inverse_ = mass_factor.solve(Eigen::MatrixXd::Identity(n_, n_));
  damping_ = s.damping;
  stiffness_ = s.stiffness;
  loads_ = s.loads;
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const Law* law = model.laws[l].law.get();
    Site site;
    site.dof = model.laws[l].dofs[0];
    if (const auto* cubic = dynamic_cast<const CubicStiffness*>(law)) {
      site.cubic = true;
      site.coefficient = cubic->epsilon();
    } else if (const auto* planar = dynamic_cast<const Coulomb2D*>(law)) {
      site.second_dof = model.laws[l].dofs[1];
      site.coefficient = planar->muN();
    } else {
      throwInputError("law[" + std::to_string(l) + "].type", law->type(),
                      "exact orbits handle coulomb-1d, signorini (event-driven), cubic and sliding coulomb-2d "
                      "(smooth) laws, not mixed");
    }
    components_ += site.cubic ? 1 : 2;
    sites_.push_back(site);
  }
  double rate = std::max(std::sqrt((mass_inverse_ * stiffness_).cwiseAbs().rowwise().sum().maxCoeff()),
                         (mass_inverse_ * damping_).cwiseAbs().rowwise().sum().maxCoeff());
  for (const auto& load : loads_) rate = std::max(rate, load.harmonic * omega_);
  rate_ = std::max(rate, omega_);
}

void SmoothFlow::lawForces(const Eigen::VectorXd& y, Eigen::Ref<Eigen::VectorXd> out) const {
  int q = 0;
  for (const Site& site : sites_) {
    if (site.cubic) {
      out[q++] = -site.coefficient * std::pow(y[site.dof], 3);
    } else {
      const double v1 = y[n_ + site.dof], v2 = y[n_ + site.second_dof], speed = std::hypot(v1, v2);
      out[q++] = -site.coefficient * v1 / speed;
      out[q++] = -site.coefficient * v2 / speed;
    }
  }
}

bool SmoothFlow::field(double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy, Eigen::MatrixXd* jacobian) const {
  Eigen::VectorXd force = -stiffness_ * y.head(n_) - damping_ * y.tail(n_);
  for (const auto& load : loads_)
    force[load.dof] += load.cos_amplitude * std::cos(load.harmonic * omega_ * t) +
                       load.sin_amplitude * std::sin(load.harmonic * omega_ * t);
  Eigen::MatrixXd dforce;  // ∂force/∂y (n x 2n)
  if (jacobian) {
    dforce.resize(n_, 2 * n_);
    dforce << -stiffness_, -damping_;
  }
  for (const Site& site : sites_) {
    if (site.cubic) {
      const double x = y[site.dof];
      force[site.dof] -= site.coefficient * x * x * x;
      if (jacobian) dforce(site.dof, site.dof) -= 3.0 * site.coefficient * x * x;
      continue;
    }
    const int a = site.dof, b = site.second_dof;
    const Eigen::Vector2d v(y[n_ + a], y[n_ + b]);
    const double speed = v.norm();
    // Rest (where 2D sticking would start): below round-off of the speeds met.
    if (!(speed > 1e-12 * (1.0 + y.tail(n_).cwiseAbs().maxCoeff()))) return false;
    force[a] -= site.coefficient * v[0] / speed;
    force[b] -= site.coefficient * v[1] / speed;
    if (jacobian) {
      // ∂(−μN v/‖v‖)/∂v = −μN (I − v̂ v̂ᵀ)/‖v‖
      const Eigen::Matrix2d d = -site.coefficient * (Eigen::Matrix2d::Identity() - v * v.transpose() / (speed * speed)) / speed;
      dforce(a, n_ + a) += d(0, 0);
      dforce(a, n_ + b) += d(0, 1);
      dforce(b, n_ + a) += d(1, 0);
      dforce(b, n_ + b) += d(1, 1);
    }
  }
  dy.resize(2 * n_);
  dy.head(n_) = y.tail(n_);
  dy.tail(n_) = mass_inverse_ * force;
  if (jacobian) {
    jacobian->setZero(2 * n_, 2 * n_);
    jacobian->topRightCorner(n_, n_).setIdentity();
    jacobian->bottomRows(n_) = mass_inverse_ * dforce;
  }
  return true;
}

bool SmoothFlow::step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y1, Eigen::MatrixXd* dy1) const {
  const int d = 2 * n_;
  Eigen::VectorXd f0;
  if (!field(t, y, f0, nullptr)) return false;
  Eigen::VectorXd k(3 * d), stage(d), fi;
  for (int i = 0; i < 3; ++i) k.segment(i * d, d) = f0;
  Eigen::MatrixXd jac[3];
  Eigen::MatrixXd newton(3 * d, 3 * d);
  Eigen::VectorXd residual(3 * d);
  bool converged = false;
  for (int it = 0; it < 30; ++it) {
    for (int i = 0; i < 3; ++i) {
      stage = y;
      for (int j = 0; j < 3; ++j) stage += h * kA[i][j] * k.segment(j * d, d);
      if (!field(t + kC[i] * h, stage, fi, &jac[i])) return false;
      residual.segment(i * d, d) = k.segment(i * d, d) - fi;
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        newton.block(i * d, j * d, d, d) = -h * kA[i][j] * jac[i];
    newton.diagonal().array() += 1.0;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(newton);
    const Eigen::VectorXd delta = lu.solve(residual);
    k -= delta;
    if (delta.cwiseAbs().maxCoeff() <= 4.0 * std::numeric_limits<double>::epsilon() * (k.cwiseAbs().maxCoeff() + 1e-300)) {
      converged = true;
      if (dy1) {
        // Derivative of the converged stages (the last Newton matrix is at
        // the iterate before the final correction: close enough to round-off
        // once the correction is at round-off).
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

FlowResult SmoothFlow::integrate(const Eigen::VectorXd& y0, double t0, double duration, bool with_jacobian,
                                 FlowSamples* samples) const {
  FlowResult result;
  const int d = 2 * n_;
  if (y0.size() != d || !y0.allFinite() || !(duration >= 0.0) || !std::isfinite(t0)) {
    result.failure = "initial state or interval not finite or of the wrong size";
    return result;
  }
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Identity(d, d);
  result.max_abs = y0.head(n_).cwiseAbs();
  if (samples) {
    samples->displacement.resize(samples->times.size(), n_);
    samples->velocity.resize(samples->times.size(), n_);
    samples->force.resize(samples->times.size(), components_);
  }
  size_t next_sample = 0;
  Eigen::VectorXd y = y0, big, half, small;
  Eigen::MatrixXd d_big, d_half, d_small;
  double t = t0, h = std::min(duration, 0.05 / rate_);
  const double t_end = t0 + duration;
  int steps = 0;
  auto failAtRest = [&](double when) {
    result.failure = "2D friction comes to rest at t = " + formatNumber(when) +
                     " (sticking in the plane is not integrated)";
    return result;
  };
  while (t < t_end) {
    h = std::min(h, t_end - t);
    if (++steps > kMaxSteps || h <= 1e-14 * (std::abs(t) + duration)) {
      if (!step(t, y, h, big, nullptr)) return failAtRest(t);
      result.failure = "step size underflow at t = " + formatNumber(t);
      return result;
    }
    // Step doubling: one step of h against two of h/2.
    const bool ok = step(t, y, h, big, nullptr) && step(t, y, 0.5 * h, half, with_jacobian ? &d_half : nullptr) &&
                    step(t + 0.5 * h, half, 0.5 * h, small, with_jacobian ? &d_small : nullptr);
    if (!ok) {
      if (h < 1e-9 * duration) return failAtRest(t);
      h *= 0.25;
      continue;
    }
    const double error = (big - small).cwiseAbs().maxCoeff() / 63.0;
    const double scale = std::max(1.0, small.cwiseAbs().maxCoeff());
    const double grow = error > 0 ? 0.9 * std::pow(kLocalTolerance * scale / error, 1.0 / 7.0) : 2.0;
    if (error > kLocalTolerance * scale) {
      h *= std::max(0.2, grow);
      continue;
    }
    // Accepted [t, t + h]: extremes of x_i (zeros of v_i) and samples by one
    // Gauss step from t.
    auto at = [&](double tau) {
      Eigen::VectorXd out;
      if (tau <= 0.0) return y;
      // Inside an accepted step the speed stays away from rest; if a
      // shorter step still fails, the step's end stands in.
      if (!step(t, y, tau, out, nullptr)) return small;
      return out;
    };
    for (int i = 0; i < n_; ++i) {
      result.max_abs[i] = std::max(result.max_abs[i], std::abs(small[i]));
      const double va = y[n_ + i], vb = small[n_ + i];
      if ((va > 0.0) != (vb > 0.0) && va != 0.0) {
        double lo = 0.0, hi = h;
        for (int it = 0; it < 60 && hi - lo > 1e-15 * (std::abs(t) + duration); ++it) {
          const double mid = 0.5 * (lo + hi);
          ((at(mid)[n_ + i] > 0.0) == (va > 0.0) ? lo : hi) = mid;
        }
        result.max_abs[i] = std::max(result.max_abs[i], std::abs(at(hi)[i]));
      }
    }
    if (samples) {
      for (; next_sample < samples->times.size() && samples->times[next_sample] <= t + h; ++next_sample) {
        const Eigen::VectorXd ys = at(samples->times[next_sample] - t);
        samples->displacement.row(next_sample) = ys.head(n_).transpose();
        samples->velocity.row(next_sample) = ys.tail(n_).transpose();
        Eigen::VectorXd f(components_);
        lawForces(ys, f);
        samples->force.row(next_sample) = f.transpose();
      }
    }
    if (with_jacobian) jacobian = d_small * d_half * jacobian;
    y = small;
    t += h;
    h *= std::min(2.0, grow);
  }
  result.end = y;
  if (with_jacobian) result.jacobian = jacobian;
  result.ok = true;
  result.phases = 1;
  return result;
}

}  // namespace eqhb::orbits
