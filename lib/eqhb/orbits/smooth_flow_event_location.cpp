// Event location of SmoothFlow (smooth_flow_integration.h): the watched
// functions g(t, y) > 0 of the phase are bracketed at the half and the end
// of each step and their first zero located by the Illinois method on the
// Gauss solution, to round-off in t.
#include <cmath>
#include <limits>

#include "eqhb/orbits/smooth_flow_integration.h"

namespace eqhb::orbits {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
}  // namespace

SmoothFlow::Integration::FirstEvent SmoothFlow::Integration::locateFirstEvent(const std::vector<Watch>& watch,
                                                                             double span) {
  FirstEvent first;
  first.tau = span;
  for (size_t e = 0; e < watch.size(); ++e) {
    const std::optional<double> tau = locateEvent(watch[e], span);
    if (tau && (first.watch < 0 || *tau < first.tau)) {
      first.watch = static_cast<int>(e);
      first.tau = *tau;
    }
  }
  return first;
}

std::optional<double> SmoothFlow::Integration::locateEvent(const Watch& w, double span) {
  const double g_half = flow_.eventValue(w, t_ + 0.5 * span, half_, modes_, nullptr, nullptr);
  const double g_end = flow_.eventValue(w, t_ + span, small_, modes_, nullptr, nullptr);
  double hi = g_half > 0.0 ? span : 0.5 * span;
  if (g_half > 0.0 && g_end > 0.0) {
    const std::optional<double> dip = dipBelowZero(w, span);
    if (!dip) return std::nullopt;
    hi = *dip;
  }
  const double g_lo = eventFunction(w, 0.0), g_hi = eventFunction(w, hi);
  if (!(g_hi <= 0.0)) return std::nullopt;
  // Leaves its set at once: the event fires at the start.
  if (!(g_lo > 0.0)) return 0.0;
  return illinois(w, 0.0, hi, g_lo, g_hi);
}

std::optional<double> SmoothFlow::Integration::dipBelowZero(const Watch& w, double span) {
  // Positive at the three points, g may still dip below 0 inside a half (a
  // pair of zeros closer than the step: a brief excursion of the stick
  // force, a velocity just touching 0). Where ġ goes from − to + lies a
  // minimum; if g <= 0 there, the first zero is before it.
  const double s0 = eventSlope(w, 0.0, y_), s1 = eventSlope(w, 0.5 * span, half_),
               s2 = eventSlope(w, span, small_);
  double a = 0.0, b = 0.0;
  if (s0 < 0.0 && s1 > 0.0) b = 0.5 * span;
  else if (s1 < 0.0 && s2 > 0.0) a = 0.5 * span, b = span;
  else return std::nullopt;
  for (int it = 0; it < 100 && b - a > 4.0 * kEpsilon * time_scale_; ++it) {
    const double mid = 0.5 * (a + b);
    const Eigen::VectorXd* at = stateAt(mid);
    if (!at) break;
    (eventSlope(w, mid, *at) < 0.0 ? a : b) = mid;
  }
  if (!(eventFunction(w, b) <= 0.0)) return std::nullopt;  // passes by without reaching 0
  return b;
}

double SmoothFlow::Integration::illinois(const Watch& w, double lo, double hi, double g_lo, double g_hi) {
  int side = 0;
  for (int it = 0; it < 200 && hi - lo > 4.0 * kEpsilon * time_scale_; ++it) {
    double tau = hi - g_hi * (hi - lo) / (g_hi - g_lo);
    if (!(tau > lo && tau < hi)) tau = 0.5 * (lo + hi);
    const double value = eventFunction(w, tau);
    if (std::isnan(value)) break;
    if (value > 0.0) {
      lo = tau;
      g_lo = value;
      if (side == -1) g_hi *= 0.5;  // Illinois
      side = -1;
    } else {
      hi = tau;
      g_hi = value;
      if (side == 1) g_lo *= 0.5;
      side = 1;
      if (value == 0.0) break;
    }
  }
  return hi;
}

double SmoothFlow::Integration::eventFunction(const Watch& w, double tau) {
  const Eigen::VectorXd* at = stateAt(tau);
  return at ? flow_.eventValue(w, t_ + tau, *at, modes_, nullptr, nullptr) : kNaN;
}

double SmoothFlow::Integration::eventSlope(const Watch& w, double tau, const Eigen::VectorXd& y_at) {
  Eigen::RowVectorXd gradient;
  double time_derivative = 0.0;
  Eigen::VectorXd f;
  flow_.eventValue(w, t_ + tau, y_at, modes_, &gradient, &time_derivative);
  return flow_.field(t_ + tau, y_at, modes_, f, nullptr) ? time_derivative + gradient.dot(f) : 0.0;
}

const Eigen::VectorXd* SmoothFlow::Integration::stateAt(double tau) {
  if (tau <= 0.0) return &y_;
  if (!flow_.step(t_, y_, 0.5 * tau, modes_, scratch_quarter_, nullptr) ||
      !flow_.step(t_ + 0.5 * tau, scratch_quarter_, 0.5 * tau, modes_, scratch_end_, nullptr))
    return nullptr;
  return &scratch_end_;
}

}  // namespace eqhb::orbits
