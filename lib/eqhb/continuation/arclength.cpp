// sweepArclength: pseudo-arclength continuation in ω (continuation.h).
//
// Each step, like a minimizer's iteration: scale the unknowns by the current
// point's magnitude, predict along the tangent, correct on the bordered
// system, then test the new point (did it leave the range? did the tangent
// turn too far?) before accepting it and adapting the step.
#include <algorithm>
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
// met so far, or of the problem's own size of z (HbSystem::unknownScale):
// near rest (an antiresonance) a relative scale would blow up, and on a
// stretch where every law is idle (a contact not yet reached) the condensed
// unknowns are exactly zero: a floor from ‖z‖ alone would make the first
// contact force infinitely large in the scaled unknowns.
constexpr double kScaleFloorFraction = 1e-3;

// The bordered corrector and the tangent are dense: the full system takes
// over from a condensed one (switchToFullSystem) only up to this size (an LU
// of 2000 unknowns, ~3 GFLOP and 32 MB; a beam's full system of 10⁵ would
// need 80 GB).
constexpr int kMostDenseUnknowns = 2000;

// Where a bridge tries its fixed-ω point: these fractions of the range ahead.
constexpr double kBridgeFractions[] = {1e-3, 1e-2, 3e-2};
// A curve bridged this often is not being traced by arclength any more.
constexpr int kMostBridges = 10;
// Local parametrisation by ω (ArclengthSweep::correctAtFixedOmega) only
// where ω carries at least this share of the unit tangent (a fold is near
// where it carries less).
constexpr double kLocalOmega = 0.01;
// A point found with ω held lies within this many steps of the current one.
constexpr double kLocalReach = 2.0;

struct ArcPoint {
  Eigen::VectorXd z;
  double omega = 0.0;
  Eigen::VectorXd direction;  // tangent (dz, dω) in physical units
};

double angleBetween(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
}

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
    unknown_scale_ = system_->unknownScale();
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
      FallbackReport tried;
      first = solveWithFallbacks(*system_, solver_, solver_options_, first, false, options_.fallbacks, &tried);
      if (!first.converged()) {
        stop("no solution at the start " + at(options_.from) + " (" + terminationName(first.termination) +
             "; fallbacks: " + describeFallbacks(tried) + ")");
        return false;
      }
    }
    current_.z = first.solution;
    current_.omega = options_.from;
    largest_norm_ = current_.z.norm();
    Eigen::VectorXd guess = Eigen::VectorXd::Zero(n_ + 1);
    guess[n_] = direction_;
    const ArcScales s = scales();
    Eigen::VectorXd tangent;
    if (!tangentAt(*system_, s, s.scaled(current_.z, current_.omega), guess, &tangent) &&
        !secantTangent(s, direction_, &tangent)) {
      stop("no tangent at the start " + at(options_.from) +
           " (singular bordered Jacobian, and no solution a little further in omega for a secant)");
      return false;
    }
    current_.direction = s.physicalDirection(tangent);
    record(current_, first, tangent[n_]);
    return true;
  }

  void trace() {
    ArclengthStep step(options_);
    KinkTest kink;
    // Where the curve cannot be followed: bridge to a point further on and
    // start afresh there (true: go on), or stop saying why (false).
    auto bridgeOrStop = [&](const std::string& reason) {
      if (static_cast<int>(bridged_.size()) >= kMostBridges) {
        stop(reason + "; the curve was bridged " + std::to_string(bridged_.size()) +
             " times already: arclength cannot follow it here, sweep it sequentially");
        return false;
      }
      if (switchToFullSystem() || bridge()) {
        step = ArclengthStep(options_);
        kink.reset();
        if (current_.omega != options_.to) return true;
        finishAtTheEnd();
        return false;
      }
      stop(reason + "; no point found a little further in omega either (fallbacks included)");
      return false;
    };
    while (static_cast<int>(curve_.points.size()) < options_.max_points) {
      const ArcScales s = scales();
      const Eigen::VectorXd y = s.scaled(current_.z, current_.omega);
      const Eigen::VectorXd t = s.scaledDirection(current_.direction);
      const Eigen::VectorXd predicted = y + step.size() * t;
      BorderedSystem bordered(*system_, s);
      bordered.setConstraint(t, predicted);
      // Once the bordered corrector has stalled where the fixed-ω one got
      // through, ω stays the parameter while it carries the tangent.
      const bool local = std::abs(t[n_]) >= kLocalOmega;
      if (!local) by_omega_ = false;
      SolverResult r = by_omega_ ? correctAtFixedOmega(s, y, t, step.size()) : solver_.solve(bordered, predicted, solver_options_);
      if (!r.converged() && local) {
        SolverResult other = by_omega_ ? solver_.solve(bordered, predicted, solver_options_)
                                       : correctAtFixedOmega(s, y, t, step.size());
        if (other.converged()) {
          by_omega_ = !by_omega_;
          r = std::move(other);
        }
      }
      if (!r.converged()) {
        if (step.halve()) continue;
        if (bridgeOrStop("the corrector failed (" + std::string(terminationName(r.termination)) + ") near " +
                         at(current_.omega) + " even with the step at min_step = " +
                         formatNumber(options_.min_step) + ": give a smaller min_step, or try system = full or "
                         "another solver"))
          continue;
        return;
      }
      const Eigen::VectorXd& y_new = r.solution;
      const double omega_new = y_new[n_] * s.omega;
      if (omega_new < lo_ || omega_new > hi_) {
        if (landOnTheEnd(s, y, y_new, step.size())) return;
        if (!step.halve())
          return stop("no solution at the end of the range next to " + at(current_.omega) +
                           " even with the step at min_step = " + formatNumber(options_.min_step));
        continue;
      }
      Eigen::VectorXd t_new;
      const bool regular = tangentAt(*system_, s, y_new, t, &t_new);
      if (!regular) {
        // A singular Jacobian along the curve (a stuck slider's undetermined
        // mean): the secant is the direction the curve took.
        t_new = (y_new - y).normalized();
      }
      if (!t_new.allFinite()) {
        if (step.halve() || bridgeOrStop("no tangent (singular bordered Jacobian) at " + at(omega_new) +
                                          ": a bifurcation point; give a smaller min_step to step across it"))
          continue;
        return;
      }
      double turn = angleBetween(t, t_new);
      if (turn > options_.max_turn) {
        // A smooth bend: a shorter step turns less. A kink (the tangent
        // jumps, as where a law switches regime, or the Jacobian gives a
        // spurious direction) does not shrink with the step: cross it along
        // the secant, the direction the curve actually took.
        // At min_step a turn this sharp is a kink whatever the halvings
        // showed: no smooth bend the step can resolve turns so far so soon.
        if (!kink.isKink(step.size(), turn) && step.halve()) continue;
        const Eigen::VectorXd along_jacobian = t_new;
        t_new = (y_new - y).normalized();
        turn = angleBetween(t, t_new);
        // Turning back in ω at a kink is a fold where the point found lies on
        // a branch of its own that goes on smoothly (a contact closing bends
        // the curve back at once: the curve's own tangent there follows the
        // secant); back on the traced path, or off it in a direction the
        // curve does not take there, the corrector did not follow the curve.
        // Where the Jacobian is singular (a slider stuck over the period: its
        // mean is free) the points off the path are that freedom, not a branch.
        const double heading = folds_.direction();
        const bool new_branch = regular && !traced_.retraces(s, y, y_new) &&
                                std::abs(along_jacobian.dot(t_new)) >= std::cos(options_.max_turn);
        if (heading != 0.0 && t_new[n_] * heading < 0.0 && !new_branch) {
          if (bridgeOrStop("the curve turns back at a kink at " + at(omega_new) +
                           " (the tangent's omega-component changes sign without passing through zero, and the "
                           "point found starts no branch of its own: not a fold); try system = full, more "
                           "samples or a smaller max_step"))
            continue;
          return;
        }
      }
      // However it turned, a curve that goes back onto the path it traced
      // (a corrector hovering where the curve ends, then retracing) has not
      // passed a fold.
      const double heading = folds_.direction();
      if (heading != 0.0 && (omega_new - current_.omega) * heading < 0.0 && traced_.retraces(s, y, y_new)) {
        if (bridgeOrStop("the curve turns back onto the path already traced at " + at(omega_new) +
                         " (not a fold); try system = full, more samples or a smaller max_step"))
          continue;
        return;
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
         ", before the end of the range: give a larger max_points or max_step");
  }

  // The corrector failed even at the smallest step (the curve's Jacobian
  // breaks down there, as at a nonsmooth law's switch): solve with ω fixed a
  // little further in the direction of travel, from the current point and
  // then by the fallback chain, and go on from there along a new tangent.
  // The point found is marked (fallback "bridge"): the curve between the two
  // points is not traced, and the jump is said in the stop reason.
  bool bridge() {
    const double heading = folds_.direction() != 0.0 ? folds_.direction() : direction_;
    for (double fraction : kBridgeFractions) {
      const double target = std::clamp(current_.omega + heading * fraction * (hi_ - lo_), lo_, hi_);
      if (target == current_.omega) return false;
      try {
        system_->setOmega(target);
      } catch (const std::exception&) {
        continue;  // singular at this ω: try further
      }
      SolverResult r = solver_.solve(*system_, current_.z, solver_options_);
      std::string taken = "bridge";
      if (!r.converged()) {
        FallbackReport tried;
        r = solveWithFallbacks(*system_, solver_, solver_options_, r, false, options_.fallbacks, &tried);
        if (!r.converged()) continue;
        taken += " (" + tried.taken + ")";
      }
      const ArcScales s = ArcScales::at(r.solution, scaleFloor(r.solution.norm()), hi_ - lo_);
      // Landed back on the path traced (a heading reversed by a spurious fold,
      // or past a fold onto the branch that led to it): no way on.
      if (traced_.retraces(s, s.scaled(current_.z, current_.omega), s.scaled(r.solution, target)) ||
          wholeCurve().retraces(s, s.scaled(current_.z, current_.omega), s.scaled(r.solution, target)))
        continue;
      Eigen::VectorXd ahead = Eigen::VectorXd::Zero(n_ + 1), tangent;
      ahead[n_] = heading;
      if (!tangentAt(*system_, s, s.scaled(r.solution, target), ahead, &tangent))
        tangent = (s.scaled(r.solution, target) - s.scaled(current_.z, current_.omega)).normalized();  // the jump's
      if (!tangent.allFinite()) continue;
      const double from = current_.omega;
      current_ = {r.solution, target, s.physicalDirection(tangent)};
      largest_norm_ = std::max(largest_norm_, current_.z.norm());
      bridged_.push_back(formatNumber(from) + " -> " + formatNumber(target));
      record(current_, r, tangent[n_], taken);
      return true;
    }
    return false;
  }

  // Every point recorded, in the current system's unknowns, each bridge's
  // jump left out: a bridge may land on the curve far behind the last
  // points traced_ keeps (stribeck at H = 40: past its second fold, 527
  // points back on the branch before the first, which it then retraced
  // to the start of the range).
  TracedPath wholeCurve() const {
    TracedPath whole(curve_.points.size());
    for (const CurvePoint& p : curve_.points) {
      if (!p.converged || p.full.size() == 0) continue;
      if (p.fallback.rfind("bridge", 0) == 0) whole.breakPath();
      whole.add(system_->fromFullCoefficients(p.full), p.omega);
    }
    return whole;
  }

  // While every law is idle (a contact not yet reached: ‖z‖ below the scale
  // floor) the condensed
  // unknowns, the law forces, are all zero: at the first touch the curve's
  // tangent there holds nothing of the motion that brought it, and where
  // the curve turns back at once (a stiff contact closing) no point lies
  // ahead of it. The full system's unknowns keep x: the curve goes on there,
  // from the same point (once, when the fallback chain has its "full" step).
  bool switchToFullSystem() {
    const auto& steps = options_.fallbacks.steps;
    if (!system_->condensed() || std::find(steps.begin(), steps.end(), "full") == steps.end()) return false;
    if (current_.z.norm() > scaleFloor(0.0)) return false;  // a law acts: bridging is the remedy there
    const HbModel& m = system_->model();
    if ((m.structure.dofs() + m.lawComponents()) * static_cast<double>(m.basis.size()) > kMostDenseUnknowns)
      return false;
    std::unique_ptr<HbSystem> full_system;
    Eigen::VectorXd full, full_before;
    try {
      system_->setOmega(current_.omega);  // the condensed x follows from λ at this ω
      full = system_->fullCoefficients(current_.z);
      model_.omega = current_.omega;
      full_system = makeHbSystem(model_, false, solver_options_.linear_algebra);
    } catch (const std::exception&) {
      return false;  // the full system does not fit, or is singular here
    }
    const Eigen::VectorXd z = full_system->fromFullCoefficients(full);
    const ArcScales s = ArcScales::at(z, std::max(kScaleFloorFraction * full_system->unknownScale(), 1e-300), hi_ - lo_);
    // Oriented along the way the curve came (the secant from the point before).
    Eigen::VectorXd came = Eigen::VectorXd::Zero(z.size() + 1), tangent;
    came[z.size()] = folds_.direction() != 0.0 ? folds_.direction() : direction_;
    if (curve_.points.size() >= 2) {
      const CurvePoint& before = curve_.points[curve_.points.size() - 2];
      came = s.scaled(z, current_.omega) - s.scaled(full_system->fromFullCoefficients(before.full), before.omega);
    }
    if (!tangentAt(*full_system, s, s.scaled(z, current_.omega), came, &tangent)) tangent = came.normalized();
    if (!tangent.allFinite()) return false;
    system_ = std::move(full_system);
    n_ = system_->size();
    unknown_scale_ = system_->unknownScale();
    current_ = {z, current_.omega, s.physicalDirection(tangent)};
    largest_norm_ = z.norm();
    by_omega_ = false;
    traced_.clear();
    full_from_ = formatNumber(current_.omega);
    return true;
  }

  // The bordered corrector can stall just above the tolerance where a
  // nonsmooth law switches: measured on the beam dampers, it ends at
  // ‖g‖ ≈ 1e-9 for a tolerance of 1e-10 on most steps, whatever the step,
  // while the same point solved with ω held converges to 1e-16 in one to
  // five iterations. Where ω moves with the curve (|τ_ω| >= kLocalOmega),
  // ω is then the curve's local parameter (Rheinboldt's local
  // parametrisation): the corrector holds ω at the predicted value and
  // solves g(z, ω) = 0 from the predicted z, `step` along `tangent` from
  // `current`. Returns the result in the scaled unknowns ŷ, like the
  // bordered corrector's.
  SolverResult correctAtFixedOmega(const ArcScales& s, const Eigen::VectorXd& current, const Eigen::VectorXd& tangent,
                                   double step) {
    const Eigen::VectorXd predicted = current + step * tangent;
    SolverResult r;
    r.termination = Termination::kEvaluationFailed;
    const double omega = predicted[n_] * s.omega;
    try {
      system_->setOmega(omega);
    } catch (const std::exception& e) {
      r.native_message = e.what();
      return r;
    }
    r = solver_.solve(*system_, predicted.head(n_) * s.z, solver_options_);
    r.solution = s.scaled(r.solution, omega);
    // Near a fold ω held may land on the branch the curve came from, or far
    // off: the point must lie ahead of the current one, within two steps.
    const Eigen::VectorXd ahead = r.solution - current;
    if (r.converged() && (ahead.dot(tangent) <= 0.0 || ahead.norm() > kLocalReach * step)) {
      r.termination = Termination::kNotProgressing;
      r.native_message = "omega held: the point found is not ahead on the curve";
    }
    return r;
  }

  // Where the bordered Jacobian is singular at the current point (a friction
  // slider stuck over the whole period leaves its mean undetermined): the
  // secant to the solution with ω fixed a little further on, heading `heading`.
  bool secantTangent(const ArcScales& s, double heading, Eigen::VectorXd* tangent) {
    const double target = std::clamp(current_.omega + heading * kBridgeFractions[0] * (hi_ - lo_), lo_, hi_);
    if (target == current_.omega) return false;
    try {
      system_->setOmega(target);
    } catch (const std::exception&) {
      return false;
    }
    const SolverResult r = solver_.solve(*system_, current_.z, solver_options_);
    try {
      system_->setOmega(current_.omega);  // back to the point the curve is at (its x is read from the system)
    } catch (const std::exception&) {
      return false;
    }
    if (!r.converged()) return false;
    *tangent = (s.scaled(r.solution, target) - s.scaled(current_.z, current_.omega)).normalized();
    return tangent->allFinite();
  }

  void finishAtTheEnd() {
    curve_.complete = true;
    stop("reached the end of the range, " + at(options_.to));
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
      finishAtTheEnd();
      return true;
    }
    stop("the curve turned back and left the range at its start, " + at(end) +
                (curve_.fold_omegas.empty() ? "" : " (after the fold at " + at(curve_.fold_omegas.back()) + ")") +
                ": not complete");
    return true;
  }

  ArcScales scales() const {
    return ArcScales::at(current_.z, scaleFloor(0.0), hi_ - lo_);
  }

  double scaleFloor(double also) const {
    return std::max(kScaleFloorFraction * std::max({largest_norm_, also, unknown_scale_}), 1e-300);
  }

  void record(const ArcPoint& point, const SolverResult& r, double tangent_omega, const std::string& fallback = "") {
    model_.omega = point.omega;
    CurvePoint p = describePoint(model_, system_->fullCoefficients(point.z));
    addSolverCounts(r, &p);
    p.fallback = fallback;
    if (!std::isnan(tangent_omega)) p.tangent_omega = tangent_omega;
    curve_.points.push_back(p);
    traced_.add(point.z, point.omega);
    const int index = static_cast<int>(curve_.points.size()) - 1;
    // Folds from the way ω actually moved between points (the secant): on a
    // nonsmooth law the Jacobian's tangent can point back in ω for a few
    // points while ω goes on (measured on a sampled penalty contact's
    // upper branch: four such "folds" after the real one). The first point
    // has only its tangent; a move ends at the point before, where a fold is.
    const bool moved = index > 0 && point.omega != curve_.points[index - 1].omega;
    if (moved || (index == 0 && !std::isnan(tangent_omega))) {
      const int fold = moved ? folds_.watch(point.omega - curve_.points[index - 1].omega, index - 1)
                             : folds_.watch(tangent_omega, index);
      if (fold >= 0) {
        curve_.points[fold].fold = true;
        curve_.fold_omegas.push_back(curve_.points[fold].omega);
      }
    }
    if (progress_) progress_(curve_.points.back(), index);
  }

  void stop(const std::string& reason) {
    curve_.stop_reason = reason;
    if (!full_from_.empty()) curve_.stop_reason += " (on the full system from omega = " + full_from_ + ")";
    if (bridged_.empty()) return;
    curve_.stop_reason += " (" + std::to_string(bridged_.size()) + " bridge(s), the curve not traced between: ";
    for (size_t i = 0; i < bridged_.size(); ++i) curve_.stop_reason += (i ? ", " : "") + bridged_[i];
    curve_.stop_reason += ")";
  }

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
  double unknown_scale_ = 0.0;  // HbSystem::unknownScale at the start
  FoldWatch folds_;
  TracedPath traced_;
  bool by_omega_ = false;  // the corrector holds ω (correctAtFixedOmega)
  std::vector<std::string> bridged_;  // "ω_from -> ω_to" of each bridge
  std::string full_from_;             // ω where the sweep went on on the full system
  Curve curve_;
};

}  // namespace

Curve sweepArclength(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                     const ContinuationOptions& options, const Progress& progress) {
  options.validate();
  return ArclengthSweep(model, solver, solver_options, options, progress).run();
}

}  // namespace eqhb
