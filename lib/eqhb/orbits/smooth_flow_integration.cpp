#include "eqhb/orbits/smooth_flow_integration.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "eqhb/error.h"
#include "eqhb/orbits/flow_integration.h"

namespace eqhb::orbits {

namespace {
constexpr int kMaxSteps = 2000000;
}  // namespace

FlowResult SmoothFlow::integrate(const Eigen::VectorXd& y0, double t0, double duration, bool with_jacobian,
                                 FlowSamples* samples) const {
  FlowResult result;
  if (!validStart(y0, 2 * n_, t0, duration, result)) return result;
  return Integration(*this, y0, t0, duration, with_jacobian, samples).run();
}

SmoothFlow::Integration::Integration(const SmoothFlow& flow, const Eigen::VectorXd& y0, double t0, double duration,
                                     bool with_jacobian, FlowSamples* samples)
    : flow_(flow), n_(flow.n_), d_(2 * flow.n_), with_jacobian_(with_jacobian), samples_(samples) {
  modes_ = flow.initialModes(t0, y0);
  y_ = y0;
  jacobian_ = Eigen::MatrixXd::Identity(d_, d_);
  // A state starting stuck: perturbations off the constraint return to it
  // at once (the stop saltation at t0).
  for (int dof : flow.constraint(modes_).dofs) {
    jacobian_.row(n_ + dof).setZero();
    y_[n_ + dof] = 0.0;
  }
  result_.max_abs = y0.head(n_).cwiseAbs();
  prepareSamples(samples, n_, flow.components_);
  t_end_ = t0 + duration;
  time_scale_ = std::abs(t0) + std::max(duration, flow.period());
  max_step_ = std::min(flow.period() / 32.0, 0.2 / flow.rate_);
  t_ = t0;
  h_ = std::min(duration, 0.05 / flow.rate_);
  rest_limit_ = std::numeric_limits<double>::infinity();
}

FlowResult SmoothFlow::Integration::run() {
  while (t_ < t_end_) {
    const double span = std::min({h_, t_end_ - t_, rest_limit_, max_step_});
    if (!stepSizeAcceptable(span)) return result_;
    if (!stepWithinTolerance(span) || passesThroughRest(span)) continue;
    const std::vector<Watch> watch = flow_.watches(modes_);
    const FirstEvent first = locateFirstEvent(watch, span);
    if (first.watch >= 0) {
      const Outcome outcome = takeEvent(watch[first.watch], first.tau, span);
      if (outcome == Outcome::kFailed) return result_;
      continue;
    }
    acceptStep(span);
    if (!bringSlidesToRest()) return result_;
  }
  result_.end = y_;
  if (with_jacobian_) result_.jacobian = jacobian_;
  result_.ok = true;
  result_.phases = 1 + static_cast<int>(events_);
  return result_;
}

// ---- step control

bool SmoothFlow::Integration::stepSizeAcceptable(double span) {
  if (++steps_ <= kMaxSteps && span > 1e-15 * time_scale_) return true;
  result_.failure = "step size underflow at t = " + formatNumber(t_);
  for (size_t s = 0; s < flow_.sites_.size(); ++s)
    if (flow_.sites_[s].kind == Kind::kPlanar && modes_[s] == Mode::kSlide && y_[n_ + flow_.sites_[s].dof] == 0.0 &&
        y_[n_ + flow_.sites_[s].second_dof] == 0.0)
      result_.failure = "planar slide from rest at t = " + formatNumber(t_) + " (law " + std::to_string(s + 1) +
                        ") too brief: its speed stays below round-off";
  return false;
}

bool SmoothFlow::Integration::stepWithinTolerance(double span) {
  // Step doubling: one step of h against two of h/2.
  const bool ok = flow_.step(t_, y_, span, modes_, big_, nullptr) &&
                  flow_.step(t_, y_, 0.5 * span, modes_, half_, with_jacobian_ ? &d_half_ : nullptr) &&
                  flow_.step(t_ + 0.5 * span, half_, 0.5 * span, modes_, small_, with_jacobian_ ? &d_small_ : nullptr);
  if (!ok) {
    h_ = 0.25 * span;
    return false;
  }
  const double error = (big_ - small_).cwiseAbs().maxCoeff() / 63.0;
  const double scale = std::max(1.0, small_.cwiseAbs().maxCoeff());
  grow_ = error > 0 ? 0.9 * std::pow(kLocalTolerance * scale / error, 1.0 / 7.0) : 2.0;
  if (error > kLocalTolerance * scale) {
    h_ = span * std::max(0.2, grow_);
    return false;
  }
  return true;
}

bool SmoothFlow::Integration::passesThroughRest(double span) {
  // A planar slide whose velocity turned by more than a right angle went
  // through rest inside the step: shorter steps.
  bool through_rest = false;
  for (size_t s = 0; s < flow_.sites_.size(); ++s) {
    const Site& site = flow_.sites_[s];
    if (site.kind == Kind::kPlanar && modes_[s] == Mode::kSlide &&
        y_[n_ + site.dof] * small_[n_ + site.dof] + y_[n_ + site.second_dof] * small_[n_ + site.second_dof] < 0.0)
      through_rest = true;
  }
  if (!through_rest) return false;
  h_ = 0.5 * span;
  rest_limit_ = std::min(rest_limit_, h_);
  return true;
}

void SmoothFlow::Integration::acceptStep(double span) {
  record(span, small_);
  if (with_jacobian_) jacobian_ = d_small_ * d_half_ * jacobian_;
  t_ += span;
  y_ = small_;
  h_ = span * std::min(2.0, grow_);
  rest_limit_ = std::numeric_limits<double>::infinity();
}

// ---- recording

Eigen::VectorXd SmoothFlow::Integration::stateOnStep(double tau, double span, const Eigen::VectorXd& y_end) const {
  Eigen::VectorXd out;
  if (tau <= 0.0) return y_;
  if (tau >= span || !flow_.step(t_, y_, tau, modes_, out, nullptr)) return y_end;
  return out;
}

void SmoothFlow::Integration::record(double span, const Eigen::VectorXd& y_end) {
  for (int i = 0; i < n_; ++i) {
    result_.max_abs[i] = std::max(result_.max_abs[i], std::abs(y_end[i]));
    const double va = y_[n_ + i], vb = y_end[n_ + i];
    if ((va > 0.0) != (vb > 0.0) && va != 0.0 && vb != 0.0) {
      double lo = 0.0, hi = span;
      for (int it = 0; it < 60 && hi - lo > 1e-15 * time_scale_; ++it) {
        const double mid = 0.5 * (lo + hi);
        ((stateOnStep(mid, span, y_end)[n_ + i] > 0.0) == (va > 0.0) ? lo : hi) = mid;
      }
      result_.max_abs[i] = std::max(result_.max_abs[i], std::abs(stateOnStep(hi, span, y_end)[i]));
    }
  }
  if (!samples_) return;
  for (; next_sample_ < samples_->times.size() && samples_->times[next_sample_] <= t_ + span; ++next_sample_) {
    const Eigen::VectorXd ys = stateOnStep(samples_->times[next_sample_] - t_, span, y_end);
    samples_->displacement.row(next_sample_) = ys.head(n_).transpose();
    samples_->velocity.row(next_sample_) = ys.tail(n_).transpose();
    int q = 0;
    for (size_t s = 0; s < flow_.sites_.size(); ++s) {
      const Eigen::VectorXd f = flow_.siteForce(static_cast<int>(s), samples_->times[next_sample_], ys, modes_);
      for (int k = 0; k < f.size(); ++k) samples_->force(next_sample_, q++) = f[k];
    }
  }
}

}  // namespace eqhb::orbits
