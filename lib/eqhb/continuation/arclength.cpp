// sweepArclength: pseudo-arclength continuation in ω (continuation.h).
//
// Each step, like a minimizer's iteration: scale the unknowns by the current
// point's magnitude, predict along the tangent, correct on the bordered
// system, then test the new point (did it leave the range? did the tangent
// turn too far?) before accepting it and adapting the step.
#include <chrono>
#include <cmath>

#include "eqhb/continuation/arclength_steps.h"
#include "eqhb/continuation/bordered_system.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {
namespace {

// The scale of z never drops below this fraction of the largest magnitude
// met so far: near rest (an antiresonance) a relative scale would blow up.
constexpr double kScaleFloorFraction = 1e-3;

struct ArcPoint {
  Eigen::VectorXd z;
  double omega = 0.0;
  Eigen::VectorXd direction;  // tangent (dz, dω) in physical units
};

double angleBetween(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
}

double degrees(double radians) { return radians * 180.0 / M_PI; }

std::string at(double omega) { return "omega = " + formatNumber(omega); }

class ArclengthSweep {
 public:
  ArclengthSweep(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                 const ContinuationOptions& options, const Progress& progress)
      : model_(model),
        solver_(solver),
        solver_options_(solver_options),
        options_(options),
        progress_(progress),
        lo_(std::min(options.from, options.to)),
        hi_(std::max(options.from, options.to)),
        direction_(options.to > options.from ? 1.0 : -1.0) {
    model_.omega = options.from;
    system_ = makeHbSystem(model_, options.condensed, solver_options.linear_algebra);
    n_ = system_->size();
  }

  Curve run() {
    const auto start = std::chrono::steady_clock::now();
    if (startCurve()) trace();
    curve_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(curve_);
  }

 private:
  // The first point: a plain solve at `from`, else by continuation in H;
  // its tangent points towards `to`.
  bool startCurve() {
    const Eigen::VectorXd z0 = options_.start_full.size() ? system_->fromFullCoefficients(options_.start_full)
                                                          : Eigen::VectorXd::Zero(n_);
    SolverResult first = solver_.solve(*system_, z0, solver_options_);
    if (!first.converged()) {
      Eigen::VectorXd full;
      first = solveByHarmonicContinuation(model_, solver_, solver_options_, 1, options_.condensed, &full);
      if (first.converged()) first.solution = system_->fromFullCoefficients(full);
    }
    if (!first.converged()) {
      stop("no solution at the start " + at(options_.from) + " (" + terminationName(first.termination) +
           "): try --full or another --solver");
      return false;
    }
    current_.z = first.solution;
    current_.omega = options_.from;
    largest_norm_ = current_.z.norm();
    Eigen::VectorXd guess = Eigen::VectorXd::Zero(n_ + 1);
    guess[n_] = direction_;
    const ArcScales s = scales();
    Eigen::VectorXd tangent;
    if (!tangentAt(*system_, s, s.scaled(current_.z, current_.omega), guess, &tangent)) {
      stop("no tangent at the start " + at(options_.from) + " (singular bordered Jacobian)");
      return false;
    }
    current_.direction = s.physicalDirection(tangent);
    record(current_, first, tangent[n_]);
    return true;
  }

  void trace() {
    ArclengthStep step(options_);
    KinkTest kink;
    while (static_cast<int>(curve_.points.size()) < options_.max_points) {
      const ArcScales s = scales();
      const Eigen::VectorXd y = s.scaled(current_.z, current_.omega);
      const Eigen::VectorXd t = s.scaledDirection(current_.direction);
      const Eigen::VectorXd predicted = y + step.size() * t;
      BorderedSystem bordered(*system_, s);
      bordered.setConstraint(t, predicted);
      const SolverResult r = solver_.solve(bordered, predicted, solver_options_);
      if (!r.converged()) {
        if (!step.halve())
          return stop("the corrector failed (" + std::string(terminationName(r.termination)) + ") near " +
                           at(current_.omega) + " even with the step at --min-step = " +
                           formatNumber(options_.min_step) + ": give a smaller --min-step, or try --full or "
                           "another --solver");
        continue;
      }
      const Eigen::VectorXd& y_new = r.solution;
      const double omega_new = y_new[n_] * s.omega;
      if (omega_new < lo_ || omega_new > hi_) {
        if (landOnTheEnd(s, y, y_new, step.size())) return;
        if (!step.halve())
          return stop("no solution at the end of the range next to " + at(current_.omega) +
                           " even with the step at --min-step = " + formatNumber(options_.min_step));
        continue;
      }
      Eigen::VectorXd t_new;
      if (!tangentAt(*system_, s, y_new, t, &t_new)) {
        if (!step.halve())
          return stop("no tangent (singular bordered Jacobian) at " + at(omega_new) +
                           ": a bifurcation point; give a smaller --min-step to step across it");
        continue;
      }
      double turn = angleBetween(t, t_new);
      if (turn > options_.max_turn) {
        // A smooth bend: a shorter step turns less. A kink (the tangent
        // jumps, as where a law switches regime, or the Jacobian gives a
        // spurious direction) does not shrink with the step: cross it along
        // the secant, the direction the curve actually took.
        if (!kink.isKink(step.size(), turn)) {
          if (!step.halve())
            return stop("the tangent turns by " + formatNumber(degrees(turn)) + " degrees at " +
                             at(omega_new) + " even with the step at --min-step = " +
                             formatNumber(options_.min_step) + ": give a smaller --min-step");
          continue;
        }
        t_new = (y_new - y).normalized();
        turn = angleBetween(t, t_new);
        const double heading = folds_.direction();
        if (heading != 0.0 && t_new[n_] * heading < 0.0)
          return stop("the curve turns back at a kink at " + at(omega_new) +
                           " (the tangent's omega-component changes sign without passing through zero: not a "
                           "fold); try --full, more --samples or a smaller --max-step");
      }
      kink.reset();
      current_.z = y_new.head(n_) * s.z;
      current_.omega = omega_new;
      current_.direction = s.physicalDirection(t_new);
      largest_norm_ = std::max(largest_norm_, current_.z.norm());
      record(current_, r, t_new[n_]);
      step.accept(r.iterations, turn);
    }
    stop("max_points = " + std::to_string(options_.max_points) + " reached at " + at(current_.omega) +
         ", before the end of the range: give a larger --max-points or --max-step");
  }

  // The corrector left the range between ŷ and ŷ_new: solve at the end it
  // crossed with ω fixed, from the chord's point there. Accepted only near
  // the chord (within one step), so that it cannot land on another branch.
  bool landOnTheEnd(const ArcScales& s, const Eigen::VectorXd& y, const Eigen::VectorXd& y_new, double step) {
    const double omega_new = y_new[n_] * s.omega;
    const double end = omega_new > hi_ ? hi_ : lo_;
    const double fraction = (end - current_.omega) / (omega_new - current_.omega);
    const Eigen::VectorXd chord = y + fraction * (y_new - y);
    try {
      system_->setOmega(end);
    } catch (const std::exception&) {
      return false;
    }
    const SolverResult r = solver_.solve(*system_, chord.head(n_) * s.z, solver_options_);
    if (!r.converged()) return false;
    const Eigen::VectorXd landed = s.scaled(r.solution, end);
    if ((landed - chord).norm() > step) return false;
    Eigen::VectorXd tangent;
    const Eigen::VectorXd heading = (y_new - y).normalized();
    const double tangent_omega = tangentAt(*system_, s, landed, heading, &tangent) ? tangent[n_] : NAN;
    record({r.solution, end, {}}, r, tangent_omega);
    if (end == options_.to) {
      curve_.complete = true;
      stop("reached the end of the range, " + at(end));
      return true;
    }
    stop("the curve turned back and left the range at its start, " + at(end) +
                (curve_.fold_omegas.empty() ? "" : " (after the fold at " + at(curve_.fold_omegas.back()) + ")") +
                ": not complete");
    return true;
  }

  ArcScales scales() const {
    return ArcScales::at(current_.z, std::max(kScaleFloorFraction * largest_norm_, 1e-12), hi_ - lo_);
  }

  void record(const ArcPoint& point, const SolverResult& r, double tangent_omega) {
    model_.omega = point.omega;
    CurvePoint p = describePoint(model_, system_->fullCoefficients(point.z));
    addSolverCounts(r, &p);
    p.tangent_omega = tangent_omega;
    curve_.points.push_back(p);
    const int index = static_cast<int>(curve_.points.size()) - 1;
    if (!std::isnan(tangent_omega)) {
      const int fold = folds_.watch(tangent_omega, index);
      if (fold >= 0) {
        curve_.points[fold].fold = true;
        curve_.fold_omegas.push_back(curve_.points[fold].omega);
      }
    }
    if (progress_) progress_(curve_.points.back(), index);
  }

  void stop(const std::string& reason) { curve_.stop_reason = reason; }

  HbModel model_;
  Solver& solver_;
  const SolverOptions& solver_options_;
  const ContinuationOptions& options_;
  const Progress& progress_;
  double lo_, hi_, direction_;
  std::unique_ptr<HbSystem> system_;
  int n_ = 0;
  ArcPoint current_;
  double largest_norm_ = 0.0;
  FoldWatch folds_;
  Curve curve_;
};

}  // namespace

Curve sweepArclength(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                     const ContinuationOptions& options, const Progress& progress) {
  options.validate();
  return ArclengthSweep(model, solver, solver_options, options, progress).run();
}

}  // namespace eqhb
