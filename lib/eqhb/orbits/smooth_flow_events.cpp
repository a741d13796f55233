// Event handling of SmoothFlow (smooth_flow_integration.h): the step to a
// located event, the modes after it and the saltation of the Jacobian; and
// planar slides brought to rest, whose sliding field is singular there (the
// rest instant is the linear extrapolation of ‖v‖, smooth_flow.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "eqhb/error.h"
#include "eqhb/orbits/flow_integration.h"
#include "eqhb/orbits/smooth_flow_integration.h"

namespace eqhb::orbits {

SmoothFlow::Integration::Outcome SmoothFlow::Integration::takeEvent(const Watch& w, double tau, double span) {
  if (tau <= 0.0) {
    if (++immediate_ > kMaxImmediateEvents) {
      result_.failure = "no consistent phase at t = " + formatNumber(t_) + " (" + w.kind + ", law " +
                        std::to_string(w.site + 1) + ")";
      return Outcome::kFailed;
    }
    y_event_ = y_;
    d_b_ = Eigen::MatrixXd::Identity(d_, d_);
    d_a_ = d_b_;
  } else if (!flow_.step(t_, y_, 0.5 * tau, modes_, quarter_, with_jacobian_ ? &d_a_ : nullptr) ||
             !flow_.step(t_ + 0.5 * tau, quarter_, 0.5 * tau, modes_, y_event_, with_jacobian_ ? &d_b_ : nullptr)) {
    h_ = 0.5 * span;
    return Outcome::kRetry;
  } else {
    immediate_ = 0;
  }
  if (!countEvent()) return Outcome::kFailed;
  record(tau, y_event_);
  if (with_jacobian_) jacobian_ = d_b_ * d_a_ * jacobian_;
  t_ += tau;
  y_ = y_event_;
  handleEvent(w);
  h_ = std::max(span, 0.01 / flow_.rate_);
  rest_limit_ = std::numeric_limits<double>::infinity();
  return Outcome::kDone;
}

void SmoothFlow::Integration::handleEvent(const Watch& w) {
  Eigen::RowVectorXd gradient;
  double g_time = 0.0;
  flow_.eventValue(w, t_, y_, modes_, &gradient, &g_time);
  Eigen::VectorXd f_before;
  const double g_rate = flow_.field(t_, y_, modes_, f_before, nullptr) ? g_time + gradient.dot(f_before) : 0.0;
  const Eigen::VectorXd y_before = y_;
  Modes after = modes_;
  std::string kind = w.kind;
  const Site& site = flow_.sites_[w.site];
  if (w.kind == "stop") {  // Stribeck velocity through 0
    y_[n_ + site.dof] = 0.0;
    after = flow_.restModes(w.site, t_, y_, modes_);
    kind = after[w.site] == Mode::kStick ? "stick" : "reversal";
  } else if (site.kind == Kind::kPlanar) {
    after[w.site] = Mode::kSlide;
  } else {
    after[w.site] = w.branch > 0 ? Mode::kSlipNegative : Mode::kSlipPositive;
  }
  applyEvent(modes_, after, y_before, gradient, g_rate, kind);
  modes_ = after;
}

// The event at (t_, y_) (y_ after any reset of v): new modes, saltation.
void SmoothFlow::Integration::applyEvent(const Modes& before, const Modes& after, const Eigen::VectorXd& y_before,
                                         const Eigen::RowVectorXd& gradient, double g_rate, const std::string& kind) {
  ++result_.events[kind];
  if (!with_jacobian_) return;
  Eigen::MatrixXd reset = Eigen::MatrixXd::Identity(d_, d_);
  for (int dof : flow_.constraint(after).dofs) reset(n_ + dof, n_ + dof) = 0.0;
  Eigen::VectorXd f_before, f_after;
  if (!flow_.field(t_, y_before, before, f_before, nullptr)) f_before = Eigen::VectorXd::Zero(d_);
  // A slide from rest starts with the sticking force: the field is
  // continuous across the release.
  if (!flow_.field(t_, y_, after, f_after, nullptr)) f_after = f_before;
  applySaltation(reset, f_before, f_after, gradient, g_rate, jacobian_);
}

bool SmoothFlow::Integration::bringSlidesToRest() {
  // Planar slides heading to rest: d‖v‖/dt = v̂ · a.
  Eigen::VectorXd f;
  if (!flow_.field(t_, y_, modes_, f, nullptr)) {
    result_.failure = "planar friction at rest in a slide at t = " + formatNumber(t_);
    return false;
  }
  for (size_t s = 0; s < flow_.sites_.size(); ++s) {
    const Site& site = flow_.sites_[s];
    if (site.kind != Kind::kPlanar || modes_[s] != Mode::kSlide) continue;
    const Eigen::Vector2d v(y_[n_ + site.dof], y_[n_ + site.second_dof]),
        a(f[n_ + site.dof], f[n_ + site.second_dof]);
    const double speed = v.norm(), rate = v.dot(a) / speed;
    if (!(rate < 0.0)) continue;
    const double to_rest = speed / -rate;
    // Rest when the predicted time to it is tiny, or the speed is within
    // a hundred times the round-off floor of the field (slow approaches).
    const bool resting = to_rest <= kRestTime * time_scale_ ||
                         speed <= 100.0 * kRestSpeed * (1.0 + y_.tail(n_).cwiseAbs().maxCoeff());
    if (!resting || t_ + to_rest >= t_end_) {
      rest_limit_ = std::min(rest_limit_, 0.9 * to_rest);
      continue;
    }
    if (!countEvent()) return false;
    restPlanarSlide(static_cast<int>(s), f, to_rest, rate);
    break;
  }
  return true;
}

// At rest: linear extrapolation over the remaining to_rest.
void SmoothFlow::Integration::restPlanarSlide(int s, const Eigen::VectorXd& f, double to_rest, double rate) {
  const Site& site = flow_.sites_[s];
  const double speed = Eigen::Vector2d(y_[n_ + site.dof], y_[n_ + site.second_dof]).norm();
  Eigen::RowVectorXd gradient = Eigen::RowVectorXd::Zero(d_);
  gradient[n_ + site.dof] = y_[n_ + site.dof] / speed;
  gradient[n_ + site.second_dof] = y_[n_ + site.second_dof] / speed;
  record(to_rest, y_ + to_rest * f);
  y_ += to_rest * f;
  t_ += to_rest;
  y_[n_ + site.dof] = y_[n_ + site.second_dof] = 0.0;
  const Modes after = flow_.restModes(s, t_, y_, modes_);
  ++result_.events[after[s] == Mode::kStick ? "stick" : "reversal"];
  if (with_jacobian_) {
    // The saltation uses the field just before rest (its limit).
    Eigen::MatrixXd reset = Eigen::MatrixXd::Identity(d_, d_);
    for (int dof : flow_.constraint(after).dofs) reset(n_ + dof, n_ + dof) = 0.0;
    Eigen::VectorXd f_after;
    if (!flow_.field(t_, y_, after, f_after, nullptr)) f_after = reset * f;
    applySaltation(reset, f, f_after, gradient, rate, jacobian_);
  }
  modes_ = after;
  rest_limit_ = std::numeric_limits<double>::infinity();
  h_ = std::max(h_, 0.01 / flow_.rate_);
}

bool SmoothFlow::Integration::countEvent() {
  if (++events_ <= kMaxEvents) return true;
  result_.failure = "more than " + std::to_string(kMaxEvents) + " events: accumulation of stick-slip";
  return false;
}

}  // namespace eqhb::orbits
