#include "eqhb/continuation/continuation.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "eqhb/continuation/failed_runs.h"
#include "eqhb/continuation/secant_guess.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

void ContinuationOptions::validate() const {
  if (!(from > 0.0) || !std::isfinite(from)) throwInputError("from", formatNumber(from), "must be finite and > 0");
  if (!(to > 0.0) || !std::isfinite(to)) throwInputError("to", formatNumber(to), "must be finite and > 0");
  if (from == to) throwInputError("to", formatNumber(to), "must differ from from");
  if (!(step > 0.0) || !std::isfinite(step)) throwInputError("step", formatNumber(step), "must be finite and > 0");
  if (!(min_step > 0.0) || !std::isfinite(min_step))
    throwInputError("min_step", formatNumber(min_step), "must be finite and > 0");
  if (!(max_step > 0.0) || !std::isfinite(max_step))
    throwInputError("max_step", formatNumber(max_step), "must be finite and > 0");
  if (min_step > max_step)
    throwInputError("min_step", formatNumber(min_step), "must be <= max_step = " + formatNumber(max_step));
  if (!(max_turn > 0.0) || !(max_turn < M_PI / 2))
    throwInputError("max_turn", formatNumber(max_turn), "must be in (0, pi/2) radians");
  if (max_points < 1) throwInputError("max_points", std::to_string(max_points), "must be >= 1");
}

double ContinuationOptions::defaultStep(double from, double to, bool arclength) {
  return arclength ? 0.01 : std::abs(to - from) / 100.0;
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

void addSolverCounts(const SolverResult& r, CurvePoint* point) {
  CurvePoint& p = *point;
  p.converged = r.converged();
  p.termination = terminationName(r.termination);
  p.iterations += r.iterations;
  p.residual_evaluations += r.residual_evaluations;
  p.jacobian_evaluations += r.jacobian_evaluations;
  p.seconds += r.seconds;
  p.residual_norm = r.final_norm;
}

namespace {

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

// Walks in ω from `at` (solution z) to `target`, the first step `first_step`,
// halved after each failed solve down to min_step: true when it arrives.
// `r` takes every converged solve (the last one at `target` on arrival),
// `counts` every solve's counts, `why` the reason ω could not be set.
bool walkInOmega(HbSystem& system, Solver& solver, const SolverOptions& solver_options, double min_step, double at,
                 Eigen::VectorXd z, double target, double first_step, SolverResult* r, CurvePoint* counts,
                 std::string* why) {
  const double direction = target > at ? 1.0 : -1.0;
  double h = first_step;
  while (h >= min_step && std::abs(target - at) > 1e-15) {
    const double next = std::abs(target - at) <= h ? target : at + direction * h;
    if (!trySetOmega(system, next, why)) return false;
    const SolverResult sub = solver.solve(system, z, solver_options);
    addSolverCounts(sub, counts);
    if (sub.converged()) {
      z = sub.solution;
      at = next;
      *r = sub;
    } else {
      h /= 2.0;
    }
  }
  return std::abs(target - at) <= 1e-15 && r->converged();
}

// A grid point that failed from the point before it (and from the fallback
// chain): past a fold the branch it came from ends, and the point may lie on
// a branch reached from the other side (the upper branch of a softening
// Duffing oscillator's jump, found from above). Walks back from the next
// grid point, converged, to `failed` with halved steps down to min_step;
// true when it arrives, the point then described.
bool solveFromAhead(HbSystem& system, HbModel& m, Solver& solver, const SolverOptions& solver_options,
                    const ContinuationOptions& options, const CurvePoint& ahead, CurvePoint* failed) {
  const double target = failed->omega;
  std::string why;
  SolverResult r;
  CurvePoint counts;
  if (!walkInOmega(system, solver, solver_options, options.min_step, ahead.omega,
                   system.fromFullCoefficients(ahead.full), target, std::abs(target - ahead.omega), &r, &counts,
                   &why))
    return false;
  CurvePoint& p = *failed;
  p.iterations += counts.iterations;
  p.residual_evaluations += counts.residual_evaluations;
  p.jacobian_evaluations += counts.jacobian_evaluations;
  p.seconds += counts.seconds;
  p.converged = true;
  p.termination = terminationName(r.termination);
  p.residual_norm = r.final_norm;
  p.fallback = "from the next point";
  m.omega = target;
  describeInto(m, system.fullCoefficients(r.solution), &p);
  return true;
}

}  // namespace

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
  // After the first converged point a failed one has continuation in ω (and
  // the next point, below) to fall back on: no forcing homotopy there.
  const FallbackChain warm_fallbacks = options.fallbacks.forWarmPoints();
  Eigen::VectorXd z = options.start_full.size() ? system->fromFullCoefficients(options.start_full)
                                                : Eigen::VectorXd::Zero(system->size());
  double last_converged_omega = NAN;
  SecantGuess guess;
  std::string stopped;  // why the curve ended before its last grid point
  for (int i = 0; i <= grid; ++i) {
    const double target = options.from + direction * i * options.step;
    if (i > 0) stopped = options.stop.due();
    if (!stopped.empty()) {
      stopped += " before omega = " + formatNumber(target) + " (" + std::to_string(grid + 1 - i) + " of " +
                 std::to_string(grid + 1) + " grid points not reached)";
      break;
    }
    CurvePoint point;
    point.omega = target;
    SolverResult r;
    std::string why;
    // Where A_k is singular at the grid point the condensed system cannot be
    // set there at all; only the full system can solve it (below).
    const bool singular = !trySetOmega(*system, target, &why);
    Eigen::VectorXd singular_full;  // that point's [x; λ]
    // Try straight; on failure, walk from the last converged ω with halved steps.
    if (!singular) {
      int evaluations = 0;
      r = solver.solve(*system, guess.at(target, *system, z, &evaluations), solver_options);
      addSolverCounts(r, &point);
      point.residual_evaluations += evaluations;
    }
    if (!point.converged && !singular && !std::isnan(last_converged_omega)) {
      point.converged = walkInOmega(*system, solver, solver_options, options.min_step, last_converged_omega, z,
                                    target, std::abs(target - last_converged_omega) / 2.0, &r, &point, &why);
    }
    const bool started_cold = std::isnan(last_converged_omega) && !options.start_full.size();
    // A start from rest that failed: by continuation in H, as the arclength's
    // first point, before the fallbacks (beam-joint-large's first point: the
    // zero start and the full system fail, the backup backend took 153
    // iterations; from H = 1 up it takes a few per rung).
    if (!point.converged && !singular && started_cold) {
      m.omega = target;
      Eigen::VectorXd full;
      const SolverResult by_harmonics =
          solveByHarmonicContinuation(m, solver, solver_options, 1, options.condensed, &full);
      addSolverCounts(by_harmonics, &point);
      if (by_harmonics.converged()) {
        r = by_harmonics;
        r.solution = system->fromFullCoefficients(full);
        point.fallback = "by continuation in H";
      }
    }
    // The halved steps leave the system at their last ω: the fallbacks solve at the grid point.
    if (!point.converged && !singular && trySetOmega(*system, target, &why)) {
      FallbackReport tried;
      const SolverResult rescued = solveWithFallbacks(*system, solver, solver_options, r, started_cold,
                                                      started_cold ? options.fallbacks : warm_fallbacks, &tried);
      for (const FallbackAttempt& attempt : tried.attempts) addSolverCounts(attempt.result, &point);
      if (rescued.converged()) {
        r = rescued;
        point.fallback = tried.taken;
      } else if (!tried.attempts.empty()) {
        why = "fallbacks: " + describeFallbacks(tried);
        point.converged = false;  // the point reports the first failure's termination
        point.termination = terminationName(r.termination);
        point.residual_norm = r.final_norm;
      }
    }
    if (singular) {
      FallbackReport tried;
      solveWhereCondensationIsSingular(system->model(), target, solver, solver_options, options.fallbacks,
                                       &singular_full, &tried);
      for (const FallbackAttempt& attempt : tried.attempts) addSolverCounts(attempt.result, &point);
      point.fallback = tried.taken;
    }
    if (point.converged) {
      // λ alone is the condensed unknowns, at any ω; x of a singular point
      // comes from its full solve (the system's factors are at another ω).
      z = singular ? system->fromFullCoefficients(singular_full) : r.solution;
      guess.accept(target, z);
      last_converged_omega = target;
      m.omega = target;
      describeInto(m, singular ? singular_full : system->fullCoefficients(z), &point);
    } else {
      ++curve.failed_points;
      if (!why.empty()) point.termination += " (" + why + ")";
    }
    curve.points.push_back(point);
    if (progress) progress(curve.points.back(), i);
  }
  // Failed points next to a converged one further on: from there, backwards
  // (a rescue like the fallbacks: not with an empty chain, --fallback none).
  const bool rescue = !options.fallbacks.steps.empty() && stopped.empty();
  for (int i = grid - 1; rescue && i >= 0 && curve.failed_points > 0; --i) {
    CurvePoint& point = curve.points[i];
    if (point.converged || !curve.points[i + 1].converged) continue;
    if (solveFromAhead(*system, m, solver, solver_options, options, curve.points[i + 1], &point))
      --curve.failed_points;
  }
  // Still failed from both sides: each neighbour's branch, by arclength.
  if (rescue && curve.failed_points > 0) followBranchesAcrossFailedRuns(model, solver, solver_options, options, &curve);
  curve.complete = curve.failed_points == 0 && stopped.empty();
  std::vector<std::string> why;  // failed points, then an early stop
  if (curve.failed_points > 0) why.push_back(std::to_string(curve.failed_points) + " grid point(s) did not converge");
  if (!stopped.empty()) why.push_back(stopped);
  curve.stop_reason = curve.complete ? "reached the end of the range" : why.size() == 2 ? why[0] + "; " + why[1] : why[0];
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
