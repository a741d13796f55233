// Event location and handling of PiecewiseLinearFlow
// (piecewise_linear_integration.h): zeros of the linear event functionals
// g = cᵀ z on the exact exponential of the phase, and at an event the reset,
// the new modes by the exact rules and the saltation of the Jacobian.
#include <cmath>
#include <limits>
#include <unsupported/Eigen/MatrixFunctions>

#include "eqhb/error.h"
#include "eqhb/orbits/flow_integration.h"
#include "eqhb/orbits/piecewise_linear_integration.h"

namespace eqhb::orbits {

double locateZero(const Eigen::RowVectorXd& c, const Eigen::MatrixXd& generator, const Eigen::VectorXd& z_a,
                  double a, double b, double time_scale, Eigen::VectorXd* z_root) {
  double lo = a, hi = b;
  const double g_lo = c.dot(z_a);
  Eigen::VectorXd z_hi = (generator * (b - a)).exp() * z_a;
  double g_hi = c.dot(z_hi);
  double tau = hi - g_hi * (hi - lo) / (g_hi - g_lo);  // secant start
  const double tolerance = 4.0 * std::numeric_limits<double>::epsilon() * time_scale;
  for (int it = 0; it < 200 && hi - lo > tolerance; ++it) {
    if (!(tau > lo && tau < hi)) tau = 0.5 * (lo + hi);
    const Eigen::VectorXd z = (generator * (tau - a)).exp() * z_a;
    const double g = c.dot(z);
    if (g > 0.0) {
      lo = tau;
    } else {
      hi = tau;
      z_hi = z;
      g_hi = g;
      if (g == 0.0) break;
    }
    const double slope = c.dot(generator * z);
    const double next = slope != 0.0 ? tau - g / slope : 0.5 * (lo + hi);
    // A Newton step that barely moves a bracket end is replaced by bisection
    // when it stalls on one side.
    tau = (next > lo && next < hi) ? next : 0.5 * (lo + hi);
  }
  *z_root = z_hi;
  return hi;
}

bool PiecewiseLinearFlow::Integration::locateEvents(const Phase& p, const std::vector<Event>& watch, double tau_a,
                                                    const Eigen::VectorXd& z_a, double tau_b,
                                                    const Eigen::VectorXd& z_b, PhaseEnd& end) {
  for (size_t e = 0; e < watch.size(); ++e) {
    const double g_a = watch[e].functional.dot(z_a), g_b = watch[e].functional.dot(z_b);
    Eigen::VectorXd z_root;
    double tau = 0.0;
    if (g_b > 0.0) {
      // Positive at both ends, g may still dip below 0 inside (a pair of
      // zeros closer than the grid: a near-grazing impact, a brief
      // excursion of the stick force). ġ = cᵀÂ z is a linear functional
      // too: where it goes from − to +, its zero is the minimum of g; if
      // g <= 0 there, the first zero lies between the start and it.
      if (!(g_a > 0.0)) continue;
      const Eigen::RowVectorXd slope = watch[e].functional * p.generator;
      if (!(slope.dot(z_a) < 0.0 && slope.dot(z_b) > 0.0)) continue;
      Eigen::VectorXd z_min;
      const double tau_min = locateZero(-slope, p.generator, z_a, tau_a, tau_b, time_scale_, &z_min);
      if (watch[e].functional.dot(z_min) > 0.0) continue;  // passes by without reaching 0
      tau = locateZero(watch[e].functional, p.generator, z_a, tau_a, tau_min, time_scale_, &z_root);
    } else if (!(g_a > 0.0)) {
      // A phase that leaves its set at once (a tie resolved one order
      // too low): the event fires at its start.
      if (tau_a != 0.0 || g_b == 0.0) continue;
      if (++immediate_events_ > kMaxImmediateEvents) {
        result_.failure = "no consistent phase at t = " + formatNumber(t_) + " (" + watch[e].kind + ", law " +
                          std::to_string(watch[e].law + 1) + ")";
        return false;
      }
      z_root = z_a;
    } else {
      tau = locateZero(watch[e].functional, p.generator, z_a, tau_a, tau_b, time_scale_, &z_root);
    }
    if (end.fired < 0 || tau < end.tau) {
      end.fired = static_cast<int>(e);
      end.tau = tau;
      end.z = z_root;
    }
  }
  return true;
}

bool PiecewiseLinearFlow::Integration::handleEvent(const Phase& p, const Event& ev) {
  if (++event_count_ > kMaxEvents) {
    result_.failure = "more than " + std::to_string(kMaxEvents) + " events: accumulation of impacts or stick-slip";
    return false;
  }
  const LawSite& site = flow_.sites_[ev.law];
  const Eigen::VectorXd f_before = (p.generator * z_).head(m_);
  const double g_rate = ev.functional.dot(p.generator * z_);
  Eigen::MatrixXd reset = Eigen::MatrixXd::Identity(m_, m_);
  std::vector<bool> free_choice(laws_, false);
  std::string kind = ev.kind;
  if (ev.kind == "stop" && site.slider >= 0) {
    // The DOF turns back with the spring force on the limit: the force
    // leaves it inwards, the slider stops (no reset of the state).
    modes_[ev.law] = Mode::kStick;
    kind = "stick";
  } else if (ev.kind == "stop") {
    z_[n_ + site.dof] = 0.0;
    free_choice[ev.law] = true;
    modes_ = flow_.chooseModes(z_, modes_, free_choice);
    kind = modes_[ev.law] == Mode::kStick ? "stick" : "reversal";
  } else if (ev.kind == "slip") {
    const double r = flow_.lawForce(ev.law, Mode::kStick, p, z_);
    modes_[ev.law] = r > 0.0 ? Mode::kSlipNegative : Mode::kSlipPositive;
  } else if (ev.kind == "touch") {
    // An elastic wall: its spring takes over from zero force, no reset.
    modes_[ev.law] = Mode::kClosed;
  } else if (ev.kind == "impact") {
    z_[site.dof] = site.gap;
    const double bounce = -flow_.restitution_ * z_[n_ + site.dof];
    if (bounce < -kPlasticImpactRatio * velocity_scale_) {
      z_[n_ + site.dof] = bounce;
      reset(n_ + site.dof, n_ + site.dof) = -flow_.restitution_;
      modes_[ev.law] = Mode::kOpen;
    } else {
      z_[n_ + site.dof] = 0.0;
      reset(n_ + site.dof, n_ + site.dof) = 0.0;
      free_choice[ev.law] = true;
      modes_ = flow_.chooseModes(z_, modes_, free_choice);
    }
  } else {  // release
    modes_[ev.law] = Mode::kOpen;
  }
  ++result_.events[kind];
  if (with_jacobian_) {
    const Phase& after = flow_.phase(modes_);
    const Eigen::VectorXd f_after = (after.generator * z_).head(m_);
    applySaltation(reset, f_before, f_after, ev.functional.head(m_), g_rate, jacobian_);
  }
  return true;
}

}  // namespace eqhb::orbits
