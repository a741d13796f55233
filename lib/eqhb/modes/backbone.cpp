#include "eqhb/modes/backbone.h"

#include <chrono>
#include <cmath>

#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/modes/mode_system.h"

namespace eqhb {

void BackboneOptions::validate(int modes) const {
  if (mode < 1 || mode > modes)
    throwInputError("mode", std::to_string(mode),
                    "must be in [1, " + std::to_string(modes) + "]: the linearised structure has " +
                        std::to_string(modes) + " mode(s)");
  if (!(from > 0.0) || !std::isfinite(from)) throwInputError("from", formatNumber(from), "must be finite and > 0");
  if (!(to > from) || !std::isfinite(to))
    throwInputError("to", formatNumber(to), "must be finite and > from (" + formatNumber(from) + ")");
  if (points < 2) throwInputError("points", std::to_string(points), "must be >= 2");
  if (max_halvings < 0) throwInputError("max_halvings", std::to_string(max_halvings), "must be >= 0");
}

double dissipatedEnergy(const HbModel& model, const Eigen::VectorXd& full, double omega, double xi) {
  const int n = model.structure.dofs(), nb = model.basis.size();
  const Eigen::Map<const Eigen::MatrixXd> x(full.data(), nb, n);
  const Eigen::MatrixXd mass_x = x * model.structure.mass;
  const auto& ks = model.basis.harmonics();
  double sum = 0.0;
  for (size_t h = 0; h < ks.size(); ++h) {
    if (ks[h] == 0) continue;
    const int o = model.basis.offset(static_cast<int>(h));
    sum += ks[h] * ks[h] * (mass_x.row(o).dot(x.row(o)) + mass_x.row(o + 1).dot(x.row(o + 1)));
  }
  return xi * M_PI * omega * sum;
}

namespace {

// The linear mode at amplitude a: x̂ = a φ cos ωt, each law's force the
// reaction A₁(ω, ξ) x̂ at its DOF (a held DOF's support force, a spring's
// force), ω and ξ = 2ζω of the mode.
Eigen::VectorXd linearStart(const ModeSystem& system, const LinearMode& mode, double a) {
  const HbModel& model = system.model();
  const int n = model.structure.dofs(), nb = model.basis.size();
  int fundamental = 0;
  for (size_t h = 0; h < model.basis.harmonics().size(); ++h)
    if (model.basis.harmonics()[h] == 1) fundamental = model.basis.offset(static_cast<int>(h));
  Eigen::VectorXd z = Eigen::VectorXd::Zero(system.size());
  for (int i = 0; i < n; ++i) z[i * nb + fundamental] = a * mode.shape[i];
  const double w = mode.omega, xi = 2.0 * mode.damping_ratio * mode.omega;
  const LinearStructure& s = model.structure;
  const Eigen::VectorXd x = a * mode.shape;
  const Eigen::VectorXd cos_row = s.stiffness * x - w * w * (s.mass * x);
  const Eigen::VectorXd sin_row = -w * (s.damping * x - xi * (s.mass * x));
  std::vector<bool> taken(n, false);
  for (int l = 0; l < static_cast<int>(model.laws.size()); ++l) {
    const AttachedLaw& attached = model.laws[l];
    for (int c = 0; c < attached.law->dimension(); ++c) {
      const int dof = attached.attachment.dof(c);  // grounded: linearModes checked
      if (taken[dof]) continue;  // a second law on one DOF starts at no force
      taken[dof] = true;
      const int row = (n + model.componentIndex(l, c)) * nb + fundamental;
      const double sign = attached.law->forceSign();
      z[row] = cos_row[dof] / sign;
      z[row + 1] = sin_row[dof] / sign;
    }
  }
  z[system.omegaIndex()] = w;
  z[system.xiIndex()] = xi;
  return z;
}

void recordSolve(const SolverResult& r, BackbonePoint* point) {
  point->iterations += r.iterations;
  point->residual_evaluations += r.residual_evaluations;
  point->jacobian_evaluations += r.jacobian_evaluations;
  point->seconds += r.seconds;
  point->termination = terminationName(r.termination);
  point->converged = r.converged();
}

// Solves at amplitude `a` from `z0`; throws InputError when the solver
// rejects its options.
SolverResult solveAt(ModeSystem& system, Solver& solver, const SolverOptions& options, double a,
                     const Eigen::VectorXd& z0) {
  system.setAmplitude(a);
  system.prepareAt(z0[system.omegaIndex()]);
  SolverResult r = solver.solve(system, z0, options);
  if (r.termination == Termination::kInvalidOptions) throw InputError("options: " + r.native_message);
  return r;
}

// The secant predictor through (s0, z0) and (s1, z1) at s (s = log a); the
// last point alone when there is no previous one, or when the secant would
// move ω by more than a factor 2 (a step across the onset of slip, where
// ω turns sharply).
Eigen::VectorXd predict(const std::vector<std::pair<double, Eigen::VectorXd>>& last, double s, int omega_index) {
  const Eigen::VectorXd& z1 = last.back().second;
  if (last.size() < 2) return z1;
  const auto& [s0, z0] = last[last.size() - 2];
  const double s1 = last.back().first;
  Eigen::VectorXd z = z1 + (z1 - z0) * ((s - s1) / (s1 - s0));
  const double ratio = z[omega_index] / z1[omega_index];
  return ratio > 0.5 && ratio < 2.0 ? z : z1;
}

BackbonePoint describe(const ModeSystem& system, const Eigen::VectorXd& z, double a) {
  BackbonePoint p;
  p.amplitude = a;
  p.full = system.fullCoefficients(z);
  p.omega = z[system.omegaIndex()];
  p.xi = z[system.xiIndex()];
  p.damping_ratio = p.xi / (2.0 * p.omega);
  p.dissipated_energy = dissipatedEnergy(system.model(), p.full, p.omega, p.xi);
  p.max_abs = describePoint(system.model(), p.full).max_abs;
  return p;
}

}  // namespace

Backbone followBackbone(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                        const BackboneOptions& o, const BackboneProgress& progress) {
  const auto start_time = std::chrono::steady_clock::now();
  const std::vector<LinearMode> modes = linearModes(model);
  o.validate(static_cast<int>(modes.size()));
  Backbone backbone;
  backbone.start = modes[o.mode - 1];
  ModeSystem system(model, backbone.start.shape);
  const double s_from = std::log(o.from), s_to = std::log(o.to);
  std::vector<std::pair<double, Eigen::VectorXd>> last;  // the last two converged (log a, z)
  for (int i = 0; i < o.points; ++i) {
    const double s_target = s_from + (s_to - s_from) * i / (o.points - 1);
    const double a_target = std::exp(s_target);
    BackbonePoint attempt;
    SolverResult r;
    if (last.empty()) {
      r = solveAt(system, solver, solver_options, a_target, linearStart(system, backbone.start, a_target));
      recordSolve(r, &attempt);
    } else {
      // Halve the step in log a until a solve succeeds, then walk on to the target.
      double s_done = last.back().first, step = s_target - s_done;
      int halvings = 0;
      while (true) {
        const double s = std::min(s_done + step, s_target);
        r = solveAt(system, solver, solver_options, std::exp(s), predict(last, s, system.omegaIndex()));
        recordSolve(r, &attempt);
        if (r.converged()) {
          last.emplace_back(s, r.solution);
          if (last.size() > 2) last.erase(last.begin());
          s_done = s;
          if (s >= s_target) break;
        } else if (++halvings > o.max_halvings) {
          break;
        } else {
          step *= 0.5;
        }
      }
    }
    BackbonePoint point = attempt;
    if (r.converged()) {
      point = describe(system, r.solution, a_target);
      point.iterations = attempt.iterations;
      point.residual_evaluations = attempt.residual_evaluations;
      point.jacobian_evaluations = attempt.jacobian_evaluations;
      point.seconds = attempt.seconds;
      point.termination = attempt.termination;
      point.converged = true;
      if (last.empty()) last.emplace_back(s_target, r.solution);
    } else {
      point.amplitude = a_target;
      ++backbone.failed_points;
    }
    backbone.points.push_back(point);
    if (progress) progress(point, i);
  }
  backbone.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return backbone;
}

}  // namespace eqhb
