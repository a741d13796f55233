#include "eqhb/orbits/piecewise_linear_integration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unsupported/Eigen/MatrixFunctions>

#include "eqhb/error.h"
#include "eqhb/orbits/flow_integration.h"

namespace eqhb::orbits {

FlowResult PiecewiseLinearFlow::integrate(const Eigen::VectorXd& y0, double t0, double duration,
                                          bool with_jacobian, FlowSamples* samples) const {
  FlowResult result;
  if (!validStart(y0, m_, t0, duration, result)) return result;
  return Integration(*this, with_jacobian, samples).run(y0, t0, duration);
}

PiecewiseLinearFlow::Integration::Integration(const PiecewiseLinearFlow& flow, bool with_jacobian,
                                              FlowSamples* samples)
    : flow_(flow),
      n_(flow.n_),
      m_(flow.m_),
      laws_(static_cast<int>(flow.sites_.size())),
      with_jacobian_(with_jacobian),
      samples_(samples) {}

bool PiecewiseLinearFlow::Integration::start(const Eigen::VectorXd& y0, double t0, double duration) {
  z_ = flow_.augment(y0, t0);
  for (const LawSite& site : flow_.sites_)
    if (site.contact && site.penalty == 0.0 && z_[site.dof] > site.gap) {
      result_.failure = "the initial state penetrates the wall (x" + std::to_string(site.dof + 1) + " = " +
                        formatNumber(z_[site.dof]) + " > gap " + formatNumber(site.gap) + ")";
      return false;
    }
  modes_ = flow_.chooseModes(z_, std::vector<Mode>(laws_, Mode::kOpen), std::vector<bool>(laws_, true));
  // A slipping elastic slider starts where its spring holds the limit:
  // w = x ∓ μN/k_t (a state beyond the limit is brought back onto it, and
  // a perturbation of w alone does not move the orbit).
  const std::vector<LawSite>& sites = flow_.sites_;
  for (int l = 0; l < laws_; ++l)
    if (sites[l].slider >= 0 && modes_[l] != Mode::kStick)
      z_[sites[l].slider] =
          z_[sites[l].dof] + (modes_[l] == Mode::kSlipPositive ? -1.0 : 1.0) * sites[l].limit / sites[l].stiffness;
  if (with_jacobian_) {
    // A state starting constrained: perturbations off the constraint return
    // to it at once (the stop / plastic-impact saltation at t0).
    jacobian_ = Eigen::MatrixXd::Identity(m_, m_);
    for (int l = 0; l < laws_; ++l) {
      if (flow_.constrains(sites[l], modes_[l])) {
        jacobian_.row(n_ + sites[l].dof).setZero();
        if (modes_[l] == Mode::kClosed) jacobian_.row(sites[l].dof).setZero();
      }
      if (sites[l].slider >= 0 && modes_[l] != Mode::kStick) {  // δw = δx
        jacobian_.row(sites[l].slider).setZero();
        jacobian_(sites[l].slider, sites[l].dof) = 1.0;
      }
    }
  }
  result_.max_abs = y0.head(n_).cwiseAbs();
  velocity_scale_ = std::max(y0.tail(n_).cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  t_end_ = t0 + duration;
  time_scale_ = std::abs(t0) + std::max(duration, flow_.period());
  prepareSamples(samples_, n_, laws_);
  t_ = t0;
  return true;
}

FlowResult PiecewiseLinearFlow::Integration::run(const Eigen::VectorXd& y0, double t0, double duration) {
  if (!start(y0, t0, duration)) return result_;
  while (true) {
    const Phase& p = flow_.phase(modes_);
    const std::vector<Event> watch = flow_.events(modes_, p);
    ++result_.phases;
    PhaseEnd end;
    if (!marchPhase(p, watch, end)) return result_;
    advance(p, end);
    if (end.fired < 0) break;
    if (!handleEvent(p, watch[end.fired])) return result_;
  }
  result_.end = z_.head(m_);
  result_.jacobian = jacobian_;
  result_.ok = true;
  return result_;
}

// ---- step control

bool PiecewiseLinearFlow::Integration::marchPhase(const Phase& p, const std::vector<Event>& watch, PhaseEnd& end) {
  Eigen::VectorXd z_a = z_, z_b;
  double tau_a = 0.0;
  const double span = t_end_ - t_;
  while (true) {
    const double tau_b = std::min(tau_a + p.grid, span);
    z_b = (tau_b - tau_a == p.grid) ? Eigen::VectorXd(p.grid_step * z_a)
                                    : Eigen::VectorXd((p.generator * (tau_b - tau_a)).exp() * z_a);
    if (!locateEvents(p, watch, tau_a, z_a, tau_b, z_b, end)) return false;
    if (end.fired >= 0) {
      record(p, tau_a, z_a, end.tau, end.z);
      return true;
    }
    record(p, tau_a, z_a, tau_b, z_b);
    if (tau_b >= span) {
      end.z = z_b;
      end.tau = tau_b;
      return true;
    }
    tau_a = tau_b;
    z_a = z_b;
  }
}

void PiecewiseLinearFlow::Integration::advance(const Phase& p, const PhaseEnd& end) {
  if (end.tau > 0.0) immediate_events_ = 0;
  if (with_jacobian_) jacobian_ = (p.generator * end.tau).exp().topLeftCorner(m_, m_) * jacobian_;
  t_ += end.tau;
  z_ = end.z;
  flow_.refreshForcing(z_, t_);
}

// ---- recording

void PiecewiseLinearFlow::Integration::record(const Phase& p, double tau_a, const Eigen::VectorXd& z_a,
                                              double tau_end, const Eigen::VectorXd& z_end) {
  // Extremes of x_i: where v_i changes sign inside the interval.
  for (int i = 0; i < n_; ++i) {
    const double va = z_a[n_ + i], vb = z_end[n_ + i];
    result_.max_abs[i] = std::max(result_.max_abs[i], std::abs(z_end[i]));
    if ((va > 0.0 && vb <= 0.0) || (va < 0.0 && vb >= 0.0)) {
      Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(flow_.nz_);
      c[n_ + i] = va > 0.0 ? 1.0 : -1.0;
      Eigen::VectorXd z_turn;
      locateZero(c, p.generator, z_a, tau_a, tau_end, time_scale_, &z_turn);
      result_.max_abs[i] = std::max(result_.max_abs[i], std::abs(z_turn[i]));
    }
  }
  velocity_scale_ = std::max(velocity_scale_, z_end.segment(n_, n_).cwiseAbs().maxCoeff());
  if (!samples_) return;
  for (; next_sample_ < samples_->times.size() && samples_->times[next_sample_] <= t_ + tau_end; ++next_sample_) {
    const double ts = samples_->times[next_sample_];
    const Eigen::VectorXd zs = (p.generator * (ts - t_ - tau_a)).exp() * z_a;
    samples_->displacement.row(next_sample_) = zs.head(n_).transpose();
    samples_->velocity.row(next_sample_) = zs.segment(n_, n_).transpose();
    for (int l = 0; l < laws_; ++l) samples_->force(next_sample_, l) = flow_.lawForce(l, modes_[l], p, zs);
  }
}

}  // namespace eqhb::orbits
