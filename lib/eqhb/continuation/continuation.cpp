#include "eqhb/continuation/continuation.h"

#include <chrono>
#include <fstream>
#include <cmath>
#include <memory>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

void ContinuationOptions::validate() const {
  if (!(from > 0.0) || !std::isfinite(from)) throwInputError("from", formatNumber(from), "must be finite and > 0");
  if (!(to > 0.0) || !std::isfinite(to)) throwInputError("to", formatNumber(to), "must be finite and > 0");
  if (from == to) throwInputError("to", formatNumber(to), "must differ from --from");
  if (!(step > 0.0) || !std::isfinite(step)) throwInputError("step", formatNumber(step), "must be finite and > 0");
  if (!(min_step > 0.0) || min_step > step) throwInputError("min_step", formatNumber(min_step), "must be in (0, step]");
  if (!(max_step >= step)) throwInputError("max_step", formatNumber(max_step), "must be >= step");
  if (max_points < 1) throwInputError("max_points", std::to_string(max_points), "must be >= 1");
}

double ContinuationOptions::gridPoints() const { return std::floor(std::abs(to - from) / step + 1e-9) + 1.0; }

void ContinuationOptions::validateGrid() const {
  validate();
  const double points = gridPoints();
  if (points > max_points)
    throwInputError("step", formatNumber(step),
                    "the grid " + formatNumber(from) + " -> " + formatNumber(to) + " needs " + formatNumber(points) +
                        " points, more than max_points = " + std::to_string(max_points) +
                        " (give a larger step or max_points)");
}

namespace {

void fillCounts(CurvePoint& p, const SolverResult& r) {
  p.converged = r.converged();
  p.termination = terminationName(r.termination);
  p.iterations += r.iterations;
  p.residual_evaluations += r.residual_evaluations;
  p.jacobian_evaluations += r.jacobian_evaluations;
  p.seconds += r.seconds;
  p.residual_norm = r.final_norm;
}

// Changing ω may fail for the condensed system (singular A_k); report it
// as a failed point rather than an exception.
bool trySetOmega(HbSystem& system, double omega, std::string* why) {
  try {
    system.setOmega(omega);
    return true;
  } catch (const std::exception& e) {
    *why = e.what();
    return false;
  }
}

}  // namespace

void writeCurveCsv(const std::string& path, const Curve& curve, int dofs) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot write the curve file");
  out << "omega,converged,termination,iterations,residual_evaluations,jacobian_evaluations,seconds";
  for (int i = 1; i <= dofs; ++i) out << ",max_abs_x" << i;
  for (int i = 1; i <= dofs; ++i) out << ",first_harmonic_x" << i;
  bool with_stability = false;
  for (const auto& p : curve.points) with_stability = with_stability || p.stable >= 0;
  bool with_estimate = false;
  for (const auto& p : curve.points) with_estimate = with_estimate || !std::isnan(p.error_estimate);
  bool with_accuracy = false;
  for (const auto& p : curve.points) with_accuracy = with_accuracy || p.accuracy_met >= 0;
  out << ",energy,fold" << (with_stability ? ",stable,bifurcation" : "") << (with_estimate ? ",error_estimate" : "")
      << (with_accuracy ? ",harmonics,samples,accuracy_met,accuracy_seconds" : "") << "\n";
  out.precision(10);
  for (const auto& p : curve.points) {
    out << p.omega << "," << (p.converged ? "true" : "false") << "," << p.termination << "," << p.iterations << ","
        << p.residual_evaluations << "," << p.jacobian_evaluations << "," << p.seconds;
    for (int i = 0; i < dofs; ++i) out << "," << (p.converged ? p.max_abs[i] : NAN);
    for (int i = 0; i < dofs; ++i) out << "," << (p.converged ? p.first_harmonic[i] : NAN);
    out << "," << (p.converged ? p.energy : NAN) << "," << (p.fold ? "true" : "false");
    if (with_stability) out << "," << (p.stable >= 0 ? std::to_string(p.stable) : "") << "," << p.bifurcation;
    if (with_estimate) out << "," << p.error_estimate;
    if (with_accuracy)
      out << "," << p.harmonics << "," << p.samples << ","
          << (p.accuracy_met >= 0 ? std::to_string(p.accuracy_met) : "") << "," << p.accuracy_seconds;
    out << "\n";
  }
}

CurvePoint describePoint(const HbModel& model, const Eigen::VectorXd& full) {
  CurvePoint p;
  p.omega = model.omega;
  describeInto(model, full, &p);
  return p;
}

void describeInto(const HbModel& model, const Eigen::VectorXd& full, CurvePoint* point) {
  CurvePoint& p = *point;
  p.full = full;
  p.max_abs.clear();
  p.first_harmonic.clear();
  const HbSolution s = summarize(model, full);
  const int n = model.structure.dofs(), nb = model.basis.size();
  for (int i = 0; i < n; ++i) {
    p.max_abs.push_back(s.displacements[i].max_abs);
    p.first_harmonic.push_back(firstHarmonicAmplitude(model.basis, full.data() + i * nb));
  }
  // Period means by Parseval: mean(a b) = a0 b0 + ½ Σ (a_k b_k + a'_k b'_k).
  Eigen::MatrixXd x(nb, n), v(nb, n);
  for (int i = 0; i < n; ++i) {
    x.col(i) = full.segment(i * nb, nb);
    differentiateCoefficients(model.basis, x.col(i).data(), model.omega, v.col(i).data());
  }
  Eigen::VectorXd weight = Eigen::VectorXd::Constant(nb, 0.5);
  if (model.basis.harmonics().front() == 0) weight[0] = 1.0;
  const Eigen::MatrixXd kx = x * model.structure.stiffness, mv = v * model.structure.mass;
  p.energy = 0.5 * (weight.asDiagonal() * (x.cwiseProduct(kx) + v.cwiseProduct(mv))).sum();
}

Curve sweepSequential(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                      const ContinuationOptions& options, const Progress& progress) {
  options.validateGrid();
  const auto start = std::chrono::steady_clock::now();
  Curve curve;
  HbModel m = model;
  m.omega = options.from;
  auto system = makeHbSystem(m, options.condensed, solver_options.linear_algebra);
  const double direction = options.to > options.from ? 1.0 : -1.0;
  const int grid = static_cast<int>(options.gridPoints()) - 1;
  Eigen::VectorXd z = options.start_full.size() ? system->fromFullCoefficients(options.start_full)
                                                : Eigen::VectorXd::Zero(system->size());
  double last_converged_omega = NAN;
  for (int i = 0; i <= grid; ++i) {
    const double target = options.from + direction * i * options.step;
    CurvePoint point;
    point.omega = target;
    SolverResult r;
    std::string why;
    // Try straight; on failure, walk from the last converged ω with halved steps.
    if (trySetOmega(*system, target, &why)) {
      r = solver.solve(*system, z, solver_options);
      fillCounts(point, r);
    }
    if (!point.converged && !std::isnan(last_converged_omega)) {
      Eigen::VectorXd walk = z;
      double at = last_converged_omega, h = std::abs(target - at) / 2.0;
      while (h >= options.min_step && std::abs(target - at) > 1e-15) {
        const double next = std::abs(target - at) <= h ? target : at + direction * h;
        if (!trySetOmega(*system, next, &why)) break;
        const SolverResult sub = solver.solve(*system, walk, solver_options);
        fillCounts(point, sub);
        if (sub.converged()) {
          walk = sub.solution;
          at = next;
          r = sub;
        } else {
          h /= 2.0;
        }
      }
      point.converged = std::abs(target - at) <= 1e-15 && r.converged();
    }
    if (point.converged) {
      z = r.solution;
      last_converged_omega = target;
      m.omega = target;
      describeInto(m, system->fullCoefficients(z), &point);
    } else {
      ++curve.failed_points;
      if (!why.empty()) point.termination += " (" + why + ")";
    }
    curve.points.push_back(point);
    if (progress) progress(curve.points.back(), i);
  }
  curve.complete = curve.failed_points == 0;
  curve.stop_reason = curve.complete ? "reached the end of the range"
                                     : std::to_string(curve.failed_points) + " grid point(s) did not converge";
  curve.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return curve;
}

namespace {

// g(z, ω) = 0 bordered by the arclength condition, in scaled unknowns.
class BorderedSystem : public SquareSystem {
 public:
  BorderedSystem(HbSystem& inner, double scale_z, double scale_omega)
      : inner_(inner), n_(inner.size()), sz_(scale_z), sw_(scale_omega), g_(n_), g_shift_(n_), jz_(n_, n_) {}
  int size() const override { return n_ + 1; }
  void setConstraint(const Eigen::VectorXd& tangent, const Eigen::VectorXd& predicted) {
    tangent_ = tangent;
    predicted_ = predicted;
  }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> out) override {
    if (!moveTo(y[n_] * sw_)) return false;
    if (!inner_.residual(y.head(n_) * sz_, out.head(n_))) return false;
    out[n_] = tangent_.dot(y - predicted_);
    return true;
  }
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::Ref<Eigen::VectorXd> out,
                           Eigen::Ref<Eigen::MatrixXd> j) override {
    const double omega = y[n_] * sw_;
    const Eigen::VectorXd z = y.head(n_) * sz_;
    // ∂g/∂ω by a forward difference (the law projection depends on ω
    // through the velocity, the condensation through every A_k).
    const double delta = 1e-7 * std::max(1.0, std::abs(omega));
    if (!moveTo(omega + delta) || !inner_.residual(z, g_shift_)) return false;
    if (!moveTo(omega) || !inner_.residualAndJacobian(z, g_, jz_)) return false;
    out.head(n_) = g_;
    out[n_] = tangent_.dot(y - predicted_);
    j.topLeftCorner(n_, n_) = jz_ * sz_;
    j.topRightCorner(n_, 1) = (g_shift_ - g_) / delta * sw_;
    j.bottomRows(1) = tangent_.transpose();
    return true;
  }

  // The inner equations in their own scales; the arclength row is scaled already.
  void residualScales(Eigen::Ref<Eigen::VectorXd> scales) const override {
    inner_.residualScales(scales.head(n_));
    scales[n_] = 1.0;
  }

 private:
  bool moveTo(double omega) {
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
  HbSystem& inner_;
  int n_;
  double sz_, sw_;
  double current_ = NAN;
  Eigen::VectorXd tangent_, predicted_, g_, g_shift_;
  Eigen::MatrixXd jz_;
};

// Unit tangent (scaled) from [J_z·s_z, J_ω·s_ω] bordered by the previous one.
bool tangentAt(HbSystem& system, const Eigen::VectorXd& y, double sz, double sw, const Eigen::VectorXd& previous,
               Eigen::VectorXd* tangent) {
  const int n = system.size();
  BorderedSystem bordered(system, sz, sw);
  bordered.setConstraint(previous, y);
  Eigen::VectorXd out(n + 1);
  Eigen::MatrixXd j(n + 1, n + 1);
  if (!bordered.residualAndJacobian(y, out, j)) return false;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
  rhs[n] = 1.0;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(j);
  if (!lu.isInvertible()) return false;
  Eigen::VectorXd t = lu.solve(rhs);
  if (!t.allFinite() || t.norm() == 0.0) return false;
  t.normalize();
  if (t.dot(previous) < 0.0) t = -t;
  *tangent = t;
  return true;
}

}  // namespace

Curve sweepArclength(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                     const ContinuationOptions& options, const Progress& progress) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  Curve curve;
  HbModel m = model;
  m.omega = options.from;
  auto system = makeHbSystem(m, options.condensed, solver_options.linear_algebra);
  const int n = system->size();
  const double direction = options.to > options.from ? 1.0 : -1.0;
  const double lo = std::min(options.from, options.to), hi = std::max(options.from, options.to);

  // First point: a plain solve at `from`, else by continuation in H.
  SolverResult first = solver.solve(
      *system, options.start_full.size() ? system->fromFullCoefficients(options.start_full) : Eigen::VectorXd::Zero(n),
      solver_options);
  if (!first.converged()) {
    Eigen::VectorXd full;
    first = solveByHarmonicContinuation(m, solver, solver_options, 1, options.condensed, &full);
    if (first.converged()) first.solution = system->fromFullCoefficients(full);
  }
  if (!first.converged()) {
    curve.stop_reason = "no solution at the start omega = " + formatNumber(options.from) + " (" +
                        terminationName(first.termination) + ")";
    curve.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return curve;
  }
  const double sz = std::max(first.solution.norm() / std::sqrt(static_cast<double>(n)), 1e-6);
  const double sw = hi - lo;
  auto record = [&](const Eigen::VectorXd& y, const SolverResult& r) {
    m.omega = y[n] * sw;
    CurvePoint p = describePoint(m, system->fullCoefficients(y.head(n) * sz));
    fillCounts(p, r);
    curve.points.push_back(p);
    if (progress) progress(curve.points.back(), static_cast<int>(curve.points.size()) - 1);
  };
  // A fold is a lasting reversal of the direction of ω along the curve; on
  // nonsmooth laws the tangent can flicker at kinks, so a reversal counts
  // only once the new direction has held for kFoldConfirmation points.
  constexpr int kFoldConfirmation = 3;
  double confirmed_direction = 0.0;
  int candidate = -1, held = 0;
  auto watchDirection = [&](double omega_component) {
    const double sign = omega_component >= 0.0 ? 1.0 : -1.0;
    if (confirmed_direction == 0.0) {
      confirmed_direction = sign;
      return;
    }
    if (sign == confirmed_direction) {
      candidate = -1;
      held = 0;
      return;
    }
    if (candidate < 0) candidate = static_cast<int>(curve.points.size()) - 1;
    if (++held >= kFoldConfirmation) {
      curve.points[candidate].fold = true;
      curve.fold_omegas.push_back(curve.points[candidate].omega);
      confirmed_direction = sign;
      candidate = -1;
      held = 0;
    }
  };
  Eigen::VectorXd y(n + 1);
  y << first.solution / sz, options.from / sw;
  record(y, first);

  Eigen::VectorXd tangent = Eigen::VectorXd::Zero(n + 1);
  tangent[n] = direction;  // initial guess of the direction: towards `to`
  if (!tangentAt(*system, y, sz, sw, tangent, &tangent)) {
    curve.stop_reason = "no tangent at the start (singular bordered Jacobian)";
    return curve;
  }
  curve.points.back().tangent_omega = tangent[n];
  watchDirection(tangent[n]);
  BorderedSystem bordered(*system, sz, sw);
  double ds = options.step;
  while (static_cast<int>(curve.points.size()) < options.max_points) {
    const Eigen::VectorXd predicted = y + ds * tangent;
    bordered.setConstraint(tangent, predicted);
    const SolverResult r = solver.solve(bordered, predicted, solver_options);
    if (!r.converged()) {
      ds /= 2.0;
      if (ds < options.min_step) {
        curve.stop_reason = "corrector failed (" + std::string(terminationName(r.termination)) +
                            ") with the step below min_step at omega = " + formatNumber(y[n] * sw);
        break;
      }
      continue;
    }
    const Eigen::VectorXd y_new = r.solution;
    Eigen::VectorXd tangent_new;
    if (!tangentAt(*system, y_new, sz, sw, tangent, &tangent_new)) {
      ds /= 2.0;
      if (ds < options.min_step) {
        curve.stop_reason = "no tangent (singular bordered Jacobian) at omega = " + formatNumber(y_new[n] * sw);
        break;
      }
      continue;
    }
    y = y_new;
    tangent = tangent_new;
    record(y, r);
    curve.points.back().tangent_omega = tangent[n];
    watchDirection(tangent[n]);
    const double omega = y[n] * sw;
    if (omega > hi + 1e-12 || omega < lo - 1e-12) {
      curve.complete = true;
      curve.stop_reason = "left the range at omega = " + formatNumber(omega);
      break;
    }
    // Fewer corrector iterations than the target: longer steps.
    const double factor = std::clamp(static_cast<double>(options.target_iterations) /
                                         std::max(1, r.iterations), 0.5, 2.0);
    ds = std::clamp(ds * factor, options.min_step, options.max_step);
  }
  if (curve.stop_reason.empty())
    curve.stop_reason = "max_points = " + std::to_string(options.max_points) + " reached at omega = " +
                        formatNumber(y[n] * sw) + ", before the end of the range";
  curve.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return curve;
}

SolverResult solveByHarmonicContinuation(const HbModel& model, Solver& solver, const SolverOptions& options,
                                         int start_harmonics, bool condensed, Eigen::VectorXd* full) {
  const int target = model.basis.count();
  HbModel current = model;
  current.basis = HarmonicSet(model.basis.kind(), std::min(std::max(start_harmonics, 1), target));
  Eigen::VectorXd seed;
  HbModel seed_model;
  SolverResult result;
  while (true) {
    auto system = makeHbSystem(current, condensed, options.linear_algebra);
    Eigen::VectorXd z0 = Eigen::VectorXd::Zero(system->size());
    if (seed.size()) z0 = system->fromFullCoefficients(transferCoefficients(seed_model, current, seed));
    result = solver.solve(*system, z0, options);
    const Eigen::VectorXd solution_full = system->fullCoefficients(result.solution);
    if (full) *full = solution_full;
    if (!result.converged() || current.basis.count() == target) return result;
    seed = solution_full;
    seed_model = current;
    current.basis = HarmonicSet(model.basis.kind(), std::min(2 * current.basis.count(), target));
  }
}

}  // namespace eqhb
