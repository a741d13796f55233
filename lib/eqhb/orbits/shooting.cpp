#include "eqhb/orbits/shooting.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/orbits/flow_dynamics.h"
#include "eqhb/solvers/deadline.h"

namespace eqhb::orbits {

void ShootingOptions::validate() const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throwInputError("shooting tolerance", formatNumber(tolerance), "must be finite and > 0");
  if (max_iterations < 1) throwInputError("shooting iterations", std::to_string(max_iterations), "must be >= 1");
  if (!(time_limit >= 0.0) || !std::isfinite(time_limit))
    throwInputError("shooting time limit", formatNumber(time_limit), "must be finite and >= 0 (0: none)");
}

namespace {

double relativeResidual(const Eigen::VectorXd& y, const Eigen::VectorXd& end) {
  const double scale = std::max(y.cwiseAbs().maxCoeff(), end.cwiseAbs().maxCoeff());
  const double r = (end - y).cwiseAbs().maxCoeff();
  return scale > 0.0 ? r / scale : r;
}

}  // namespace

ShootingResult shootFromHarmonicBalance(const Flow& flow, const HbModel& model, const Eigen::VectorXd& full,
                                        const ShootingOptions& options) {
  const double t0 = quietStartTime(model, full);
  return shootPeriodicOrbit(flow, harmonicState(model, full, t0), t0, options);
}

ShootingResult shootPeriodicOrbit(const Flow& flow, const Eigen::VectorXd& start, double start_time,
                                  const ShootingOptions& options) {
  options.validate();
  const auto clock = std::chrono::steady_clock::now;
  const auto begin = clock();
  ShootingResult out;
  out.start_time = start_time;
  const double period = flow.period();
  const int size = flow.stateSize();
  Eigen::VectorXd y = start;
  double jacobian_seconds = 0.0;
  int jacobian_runs = 0;
  double residual = std::numeric_limits<double>::infinity();
  auto evaluate = [&](const Eigen::VectorXd& state, bool with_jacobian) {
    const auto t = clock();
    FlowResult r = flow.integrate(state, start_time, period, with_jacobian);
    ++out.flow_evaluations;
    if (with_jacobian) {
      jacobian_seconds += std::chrono::duration<double>(clock() - t).count();
      ++jacobian_runs;
    }
    if (options.progress) options.progress(out.iterations, out.flow_evaluations, residual);
    return r;
  };
  const Deadline deadline(options.time_limit);
  // Once the time limit has passed: the failure, saying where shooting was.
  auto out_of_time = [&]() {
    if (!deadline.passed()) return false;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2f", deadline.elapsed());
    out.failure = "time limit reached after " + std::to_string(out.iterations) + " Newton steps and " +
                  std::to_string(out.flow_evaluations) + " period-map evaluations (" + seconds + " s of shooting)";
    return true;
  };
  FlowResult current = evaluate(y, true);
  if (!current.ok) {
    out.failure = "the period map failed at the start: " + current.failure;
    out.state = y;
    return out;
  }
  residual = relativeResidual(y, current.end);
  while (residual > options.tolerance && out.iterations < options.max_iterations && !out_of_time()) {
    const Eigen::MatrixXd newton = current.jacobian - Eigen::MatrixXd::Identity(size, size);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(newton);
    if (lu.rank() < size) {
      out.failure = "singular Newton matrix Φ − I (a multiplier equals 1)";
      break;
    }
    const Eigen::VectorXd step = lu.solve(-(current.end - y));
    ++out.iterations;
    // Backtracking: the period map is only piecewise smooth, a full step may
    // cross into another event sequence.
    bool accepted = false;
    for (double fraction = 1.0; fraction > 1e-6 && !out_of_time(); fraction *= 0.5) {
      const Eigen::VectorXd trial = y + fraction * step;
      FlowResult r = evaluate(trial, true);
      if (!r.ok) continue;
      const double trial_residual = relativeResidual(trial, r.end);
      if (trial_residual < residual || (fraction == 1.0 && trial_residual < 2.0 * residual)) {
        y = trial;
        current = std::move(r);
        residual = trial_residual;
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      if (out.failure.empty())
        out.failure = "not progressing: no step along the Newton direction lowers the period residual";
      break;
    }
  }
  out.state = y;
  out.period_residual = residual;
  out.converged = residual <= options.tolerance;
  if (!out.converged && out.failure.empty())
    out.failure = "iteration limit (" + std::to_string(options.max_iterations) + ") reached";
  out.monodromy = current.jacobian;
  if (out.converged) {
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(current.jacobian, false);
    out.multipliers = eig.eigenvalues();
    std::sort(out.multipliers.data(), out.multipliers.data() + out.multipliers.size(),
              [](const std::complex<double>& a, const std::complex<double>& b) { return std::abs(a) > std::abs(b); });
    out.spectral_radius = out.multipliers.size() ? std::abs(out.multipliers[0]) : 0.0;
    out.stable = out.spectral_radius < 1.0;
  }
  out.events = current.events;
  out.max_abs = current.max_abs;
  out.seconds = std::chrono::duration<double>(clock() - begin).count();
  out.seconds_per_orbit = jacobian_runs ? jacobian_seconds / jacobian_runs : 0.0;
  return out;
}

double distanceToOrbit(const Flow& flow, const ShootingResult& orbit, const Eigen::MatrixXd& displacement) {
  const double period = flow.period(), t0 = orbit.start_time;
  const int count = static_cast<int>(displacement.rows());
  // The orbit is sampled from its start t0: instants before t0 are taken one
  // period later (periodicity), then put in increasing order.
  std::vector<std::pair<double, int>> instants;
  for (int i = 0; i < count; ++i) {
    const double t = period * i / count;
    instants.push_back({t < t0 ? t + period : t, i});
  }
  std::sort(instants.begin(), instants.end());
  FlowSamples samples;
  for (const auto& [t, i] : instants) samples.times.push_back(t);
  if (!flow.integrate(orbit.state, t0, period, false, &samples).ok) return std::nan("");
  double worst = 0.0;
  for (int k = 0; k < count; ++k)
    worst = std::max(worst, (displacement.row(instants[k].second) - samples.displacement.row(k)).cwiseAbs().maxCoeff());
  return worst / orbit.max_abs.maxCoeff();
}

Eigen::VectorXd harmonicState(const HbModel& model, const Eigen::VectorXd& full, double t) {
  const int n = model.structure.dofs(), nb = model.basis.size();
  // Value and rate at t of the series whose coefficients start at `first`.
  auto synthesize = [&](int first, double& value, double& rate) {
    const SeriesPoint at = seriesAt(model.basis, full.data() + first, model.omega * t);
    value = at.value;
    rate = model.omega * at.slope;
  };
  std::vector<double> sliders;  // w = x + r/k_t of each Jenkins law on one DOF
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const auto slider = piecewiseLinearSite(*model.laws[l].law);  // an elastic slider: k_t > 0
    if (!slider || !(slider->stiffness > 0.0)) continue;
    double x = 0.0, r = 0.0, rate = 0.0;
    synthesize(model.laws[l].attachment.dof(0) * nb, x, rate);
    synthesize((n + model.componentIndex(static_cast<int>(l), 0)) * nb, r, rate);
    sliders.push_back(x + r / slider->stiffness);
  }
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n + static_cast<int>(sliders.size()));
  for (int i = 0; i < n; ++i) synthesize(i * nb, y[i], y[n + i]);
  for (size_t j = 0; j < sliders.size(); ++j) y[2 * n + static_cast<int>(j)] = sliders[j];
  return y;
}

double quietStartTime(const HbModel& model, const Eigen::VectorXd& full) {
  requireGroundedLaws(model.laws, "exact orbits (shooting)");
  const int samples = std::max(64, model.samples);
  const double period = 2.0 * M_PI / model.omega;
  const int n = model.structure.dofs();
  std::vector<Eigen::VectorXd> states(samples);
  for (int s = 0; s < samples; ++s) states[s] = harmonicState(model, full, period * s / samples);
  std::vector<double> score(samples, 1.0);
  for (const auto& attached : model.laws) {
    const int dof = attached.attachment.dof(0);
    auto contact = piecewiseLinearSite(*attached.law);  // a rigid wall
    if (contact && !contact->contact) contact.reset();
    if (!attached.law->usesVelocity() && !contact) continue;  // smooth in x: no event
    std::vector<double> distance(samples);
    double largest = 0.0;
    for (int s = 0; s < samples; ++s) {
      double speed = 0.0;  // sliding speed, in the plane for 2D friction
      for (int dof_k : attached.attachment.dofs()) speed = std::hypot(speed, states[s][n + dof_k]);
      distance[s] = contact ? std::max(0.0, contact->gap - states[s][dof]) : speed;
      largest = std::max(largest, distance[s]);
    }
    if (largest > 0.0)
      for (int s = 0; s < samples; ++s) score[s] = std::min(score[s], distance[s] / largest);
  }
  const auto best = std::max_element(score.begin(), score.end()) - score.begin();
  return period * best / samples;
}

}  // namespace eqhb::orbits
