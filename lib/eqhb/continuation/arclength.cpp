// sweepArclength: pseudo-arclength continuation in ω (continuation.h).
//
// Each step, like a minimizer's iteration: scale the unknowns by the current
// point's magnitude, predict along the tangent, correct on the bordered
// system, then test the new point (did the corrector converge? did it leave
// the range? is there a tangent? did the tangent turn too far? did it go back
// onto the path traced?) before accepting it and adapting the step.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "eqhb/continuation/arclength_sweep.h"
#include "eqhb/error.h"

namespace eqhb {
namespace arclength {
namespace {

// A curve bridged this often is not being traced by arclength any more.
constexpr int kMostBridges = 10;
// Local parametrisation by ω (ArclengthSweep::correctAtFixedOmega) only
// where ω carries at least this share of the unit tangent (a fold is near
// where it carries less).
constexpr double kLocalOmega = 0.01;

double angleBetween(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
}

}  // namespace

std::string at(double omega) { return "omega = " + formatNumber(omega); }

ArclengthSweep::ArclengthSweep(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                               const ContinuationOptions& options, const Progress& progress)
    : model_(model),
      solver_(solver),
      solver_options_(solver_options),
      options_(options),
      progress_(progress),
      lo_(std::min(options.from, options.to)),
      hi_(std::max(options.from, options.to)),
      direction_(options.to > options.from ? 1.0 : -1.0),
      step_(options) {
  model_.omega = options.from;
  scene_samples_ = model_.samples;
  system_ = makeHbSystem(model_, options.condensed, solver_options.linear_algebra);
  n_ = system_->size();
  unknown_scale_ = system_->unknownScale();
}

Curve ArclengthSweep::run() {
  const auto start = std::chrono::steady_clock::now();
  if (startCurve()) trace();
  curve_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return std::move(curve_);
}

// The first point: a plain solve at `from`, else by continuation in H;
// its tangent points towards `to`.
bool ArclengthSweep::startCurve() {
  const Eigen::VectorXd z0 =
      options_.start_full.size() ? system_->fromFullCoefficients(options_.start_full) : Eigen::VectorXd::Zero(n_);
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

void ArclengthSweep::trace() {
  while (static_cast<int>(curve_.points.size()) < options_.max_points) {
    if (const std::string why = options_.stop.due(); !why.empty()) {
      stop(why + " after " + at(current_.omega));
      return;
    }
    Trial trial = predictAndCorrect();
    Next next = correctorConverged(trial);
    if (next == Next::kGoOn) next = insideTheRange(trial);
    if (next == Next::kGoOn) next = tangentFound(trial);
    if (next == Next::kGoOn) next = turnedLittle(trial);
    if (next == Next::kGoOn) next = notRetracing(trial);
    if (next == Next::kStop) return;
    if (next == Next::kGoOn) accept(trial);
  }
  stop("max_points = " + std::to_string(options_.max_points) + " reached at " + at(current_.omega) +
       ", before the end of the range: give a larger max_points or max_step");
}

Trial ArclengthSweep::predictAndCorrect() {
  Trial trial;
  trial.s = scales();
  trial.y = trial.s.scaled(current_.z, current_.omega);
  trial.t = trial.s.scaledDirection(current_.direction);
  trial.r = correct(trial.s, trial.y, trial.t);
  return trial;
}

// The bordered corrector from the point predicted along τ, or the one with
// ω held (correctAtFixedOmega); where the one in use fails and ω carries the
// tangent, the other.
SolverResult ArclengthSweep::correct(const ArcScales& s, const Eigen::VectorXd& y, const Eigen::VectorXd& t) {
  const Eigen::VectorXd predicted = y + step_.size() * t;
  BorderedSystem bordered(*system_, s);
  bordered.setConstraint(t, predicted);
  // Once the bordered corrector has stalled where the fixed-ω one got
  // through, ω stays the parameter while it carries the tangent.
  const bool local = std::abs(t[n_]) >= kLocalOmega;
  if (!local) by_omega_ = false;
  SolverResult r =
      by_omega_ ? correctAtFixedOmega(s, y, t, step_.size()) : solver_.solve(bordered, predicted, solver_options_);
  if (!r.converged() && local) {
    SolverResult other =
        by_omega_ ? solver_.solve(bordered, predicted, solver_options_) : correctAtFixedOmega(s, y, t, step_.size());
    if (other.converged()) {
      by_omega_ = !by_omega_;
      r = std::move(other);
    }
  }
  return r;
}

Next ArclengthSweep::correctorConverged(const Trial& trial) {
  if (trial.r.converged()) return Next::kGoOn;
  if (step_.halve()) return Next::kRetry;
  if (const std::string end = branchEnd(trial); !end.empty()) {
    ended_at_ = current_.omega;
    return bridgeOrStop(end);
  }
  return bridgeOrStop("the corrector failed (" + std::string(terminationName(trial.r.termination)) + ") near " +
                      at(current_.omega) + " even with the step at min_step = " + formatNumber(options_.min_step) +
                      ": give a smaller min_step, or try " + (system_->condensed() ? "system = full or " : "") + "another solver");
}

// A point past either end of the range: land on the end crossed, else a
// shorter step.
Next ArclengthSweep::insideTheRange(Trial& trial) {
  trial.omega_new = trial.r.solution[n_] * trial.s.omega;
  if (!(trial.omega_new < lo_ || trial.omega_new > hi_)) return Next::kGoOn;
  // Back past the start while no fold has turned the curve: the corrector
  // went back (ipopt-ls on den-hartog-coulomb from its first point), not the
  // curve; a shorter step first.
  const bool past_the_start = (trial.omega_new - options_.from) * direction_ < 0.0;
  if (past_the_start && folds_.direction() != -direction_ && step_.halve()) return Next::kRetry;
  // Nor is a point past an end found further than the corrector reaches
  // (nlvib-03-unilateral-wall: from 0.5819, where the curve bends sharply,
  // it went past 0.5 in one step, and the landing there skipped the curve
  // between).
  const bool far = (trial.r.solution - trial.y).norm() > kLocalReach * step_.size();
  if (far && step_.halve()) return Next::kRetry;
  if (landOnTheEnd(trial.s, trial.y, trial.r.solution, step_.size()))
    return curve_.complete ? Next::kStop : leftAtTheStart();
  if (step_.halve()) return Next::kRetry;
  stop("no solution at the end of the range next to " + at(current_.omega) +
       " even with the step at min_step = " + formatNumber(options_.min_step));
  return Next::kStop;
}

// The curve turned back past its folds and left the range at its start:
// where it came back through a tangle of folds it may go on from the
// furthest point it reached (bridgeFromTheFrontier), else it stops there.
Next ArclengthSweep::leftAtTheStart() {
  if (static_cast<int>(bridged_.size()) < kMostBridges && bridgeFromTheFrontier()) return goOnFromTheNewPoint();
  stop("the curve turned back and left the range at its start, " + at(options_.from) +
       (curve_.fold_omegas.empty() ? "" : " (after the fold at " + at(curve_.fold_omegas.back()) + ")") +
       ": not complete" + unresolvedAlongTheCurve());
  return Next::kStop;
}

Next ArclengthSweep::tangentFound(Trial& trial) {
  const Eigen::VectorXd& y_new = trial.r.solution;
  trial.regular = tangentAt(*system_, trial.s, y_new, trial.t, &trial.t_new);
  // A singular Jacobian along the curve (a stuck slider's undetermined
  // mean): the secant is the direction the curve took.
  if (!trial.regular) trial.t_new = (y_new - trial.y).normalized();
  if (trial.t_new.allFinite()) return Next::kGoOn;
  if (step_.halve()) return Next::kRetry;
  return bridgeOrStop("no tangent (singular bordered Jacobian) at " + at(trial.omega_new) +
                      ": a bifurcation point; give a smaller min_step to step across it");
}

Next ArclengthSweep::turnedLittle(Trial& trial) {
  const Eigen::VectorXd& y = trial.y;
  const Eigen::VectorXd& y_new = trial.r.solution;
  trial.turn = angleBetween(trial.t, trial.t_new);
  if (!(trial.turn > options_.max_turn)) return Next::kGoOn;
  // A smooth bend: a shorter step turns less. A kink (the tangent
  // jumps, as where a law switches regime, or the Jacobian gives a
  // spurious direction) does not shrink with the step: cross it along
  // the secant, the direction the curve actually took.
  // At min_step a turn this sharp is a kink whatever the halvings
  // showed: no smooth bend the step can resolve turns so far so soon.
  if (!kink_.isKink(step_.size(), trial.turn) && step_.halve()) return Next::kRetry;
  const Eigen::VectorXd along_jacobian = trial.t_new;
  trial.t_new = (y_new - y).normalized();
  trial.turn = angleBetween(trial.t, trial.t_new);
  // Turning back in ω at a kink is a fold where the point found lies on
  // a branch of its own that goes on smoothly (a contact closing bends
  // the curve back at once: the curve's own tangent there follows the
  // secant); back on the traced path, or off it in a direction the
  // curve does not take there, the corrector did not follow the curve.
  // Where the Jacobian is singular (a slider stuck over the period: its
  // mean is free) the points off the path are that freedom, not a branch.
  const double heading = folds_.direction();
  const bool new_branch = trial.regular && !traced_.retraces(trial.s, y, y_new) &&
                          std::abs(along_jacobian.dot(trial.t_new)) >= std::cos(options_.max_turn);
  if (!(heading != 0.0 && trial.t_new[n_] * heading < 0.0 && !new_branch)) return Next::kGoOn;
  return bridgeOrStop("the curve turns back at a kink at " + at(trial.omega_new) +
                      " (the tangent's omega-component changes sign without passing through zero, and the "
                      "point found starts no branch of its own: not a fold); " + remedies());
}

// What may get past a kink the curve cannot cross: the full system is
// offered only where the curve is not on it already.
std::string ArclengthSweep::remedies() const {
  return std::string("try ") + (system_->condensed() ? "system = full, " : "") + "more samples or a smaller max_step";
}

// However it turned, a curve that goes back onto the path it traced
// (a corrector hovering where the curve ends, then retracing) has not
// passed a fold.
Next ArclengthSweep::notRetracing(const Trial& trial) {
  const double heading = folds_.direction();
  if (!(heading != 0.0 && (trial.omega_new - current_.omega) * heading < 0.0 &&
        traced_.retraces(trial.s, trial.y, trial.r.solution)))
    return Next::kGoOn;
  return bridgeOrStop("the curve turns back onto the path already traced at " + at(trial.omega_new) +
                      " (not a fold); " + remedies());
}

void ArclengthSweep::accept(const Trial& trial) {
  kink_.reset();
  current_.z = trial.r.solution.head(n_) * trial.s.z;
  current_.omega = trial.omega_new;
  current_.direction = trial.s.physicalDirection(trial.t_new);
  largest_norm_ = std::max(largest_norm_, current_.z.norm());
  record(current_, trial.r, trial.t_new[n_]);
  step_.accept(trial.r.iterations, trial.turn);
}

// Where the curve cannot be followed: bridge to a point further on and
// start afresh there (kRetry), or stop saying why (kStop).
Next ArclengthSweep::bridgeOrStop(const std::string& reason) {
  if (static_cast<int>(bridged_.size()) >= kMostBridges) {
    stop(reason + "; the curve was bridged " + std::to_string(bridged_.size()) +
         " times already: arclength cannot follow it here, sweep it sequentially" + unresolvedAlongTheCurve());
    return Next::kStop;
  }
  const double heading = folds_.direction() != 0.0 ? folds_.direction() : direction_;
  if (switchToFullSystem() || bridge(heading) || refineSamples() || bridgeFromTheFrontier())
    return goOnFromTheNewPoint();
  stop(reason + "; no point found a little further in omega either (fallbacks included)" + unresolvedAlongTheCurve());
  return Next::kStop;
}

// After a recovery put the curve on a new point: afresh from there with the
// initial step, or done where that point is the end of the range.
Next ArclengthSweep::goOnFromTheNewPoint() {
  step_ = ArclengthStep(options_);
  kink_.reset();
  if (current_.omega != options_.to) return Next::kRetry;
  finishAtTheEnd();
  return Next::kStop;
}

}  // namespace arclength

Curve sweepArclength(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                     const ContinuationOptions& options, const Progress& progress) {
  options.validate();
  return arclength::ArclengthSweep(model, solver, solver_options, options, progress).run();
}

}  // namespace eqhb
