// Where an arclength sweep (arclength_sweep.h) cannot follow the curve from
// the current point: the corrector with ω held, a bridge to a point further
// on, the switch to the full system, a secant tangent at the start, and the
// landing on an end of the range the corrector stepped past.
#include <algorithm>
#include <cmath>

#include "eqhb/continuation/arclength_sweep.h"
#include "eqhb/error.h"

namespace eqhb::arclength {
namespace {

// The bordered corrector and the tangent are dense: the full system takes
// over from a condensed one (switchToFullSystem) only up to this size (an LU
// of 2000 unknowns, ~3 GFLOP and 32 MB; a beam's full system of 10⁵ would
// need 80 GB).
constexpr int kMostDenseUnknowns = 2000;

// refineSamples doubles N at most up to this multiple of the scene's.
constexpr int kMostSampleRefinement = 4;

// branchEnd's first distance past the current point: this fraction of the range.
constexpr double kEndProbe = 1e-6;
// The least ω-component of the unit scaled tangent at a corner branchEnd
// names (below it the curve is at a smooth fold, which the corrector turns).
constexpr double kCornerOmega = 0.01;

}  // namespace

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
SolverResult ArclengthSweep::correctAtFixedOmega(const ArcScales& s, const Eigen::VectorXd& current,
                                                 const Eigen::VectorXd& tangent, double step) {
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

// The corrector failed even at the smallest step (the curve's Jacobian
// breaks down there, as at a nonsmooth law's switch): solve with ω fixed a
// little further in the direction of travel, from the current point and
// then by the fallback chain, and go on from there along a new tangent.
// The point found is marked (fallback "bridge"): the curve between the two
// points is not traced, and the jump is said in the stop reason.
bool ArclengthSweep::bridge(double heading) {
  const FallbackChain bridge_fallbacks = options_.fallbacks.withoutOmegaContinuation();
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
      r = solveWithFallbacks(*system_, solver_, solver_options_, r, false, bridge_fallbacks, &tried);
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
    bridged_.push_back(formatNumber(from) + " -> " + formatNumber(target) +
                       (ended_at_ == from ? " (the branch ends at " + formatNumber(from) + ")" : ""));
    ended_at_ = NAN;
    record(current_, r, tangent[n_], taken);
    return true;
  }
  return false;
}

// The last way on, where the curve has turned back (folds) and nothing gets
// on from where it is: a bridge ahead, in the sweep's direction, from the
// furthest point the curve reached. Why: where a law's force is not
// resolved the harmonic balance breaks its branch up into a tangle of folds
// and kinks that arclength, however small its step, follows back and forth
// (the damper at H = 20: 13 folds in 1.017-1.084, then back onto its own
// path at 1.0176) while solutions with ω held exist on past the tangle (its
// sequential sweep converges at every ω). The tangle stays in the curve as
// traced; the jump is a bridge like any other, said in the stop reason.
bool ArclengthSweep::bridgeFromTheFrontier() {
  const CurvePoint* frontier = nullptr;
  for (const CurvePoint& p : curve_.points)
    if (p.converged && p.full.size() && (!frontier || (p.omega - frontier->omega) * direction_ > 0.0)) frontier = &p;
  if (!frontier) return false;
  const bool ahead = (frontier->omega - current_.omega) * direction_ > 0.0;
  if (!ahead && folds_.direction() == direction_) return false;  // bridge() tried this way from here already
  const auto folds_since = std::count_if(curve_.points.begin() + (frontier - curve_.points.data()),
                                         curve_.points.end(), [](const CurvePoint& p) { return p.fold; });
  const ArcPoint was = current_;
  const FoldWatch folds_was = folds_;
  current_ = {system_->fromFullCoefficients(frontier->full), frontier->omega, {}};
  // The jump starts a new stretch of the path, heading as the sweep does.
  folds_ = FoldWatch();
  traced_.breakPath();
  if (!bridge(direction_)) {
    current_ = was;
    folds_ = folds_was;
    return false;
  }
  bridged_.back() += " (from the furthest point reached, " + std::to_string(folds_since) + " folds back)";
  by_omega_ = false;
  return true;
}

// Where the corrector fails at the smallest step: does the branch end at
// the current point? Solved with ω held a little further on, at two
// distances δ and 10δ, from the current point. Past the end of a branch
// the residual's least value grows in proportion to the distance (|∂g/∂ω|
// times it); where neither solve converges and the least residuals reached
// grow so (their ratio within a factor of three of 10), the branch ends
// here. Measured on the damper at H = 40: the contact's least normal force
// reaches zero at ω = 1.0759725 (about to open), and past it every backend
// stalls at ‖g‖ ≈ 0.07 (ω − 1.0759725) on either system. While the tangent
// there still points ahead in ω (a smooth fold's ω-component goes to
// zero), the curve goes on from there at a corner, which the corrector,
// predicting ahead, cannot turn. Returns the stop reason, or "" where the
// test does not hold.
std::string ArclengthSweep::branchEnd(const Trial& trial) {
  const double heading = folds_.direction() != 0.0 ? folds_.direction() : direction_;
  const double delta = kEndProbe * (hi_ - lo_);
  double least[2] = {NAN, NAN};
  for (int i = 0; i < 2; ++i) {
    const double omega = current_.omega + heading * delta * (i == 0 ? 1.0 : 10.0);
    if (omega < lo_ || omega > hi_) break;
    try {
      system_->setOmega(omega);
    } catch (const std::exception&) {
      break;
    }
    const SolverResult r = solver_.solve(*system_, current_.z, solver_options_);
    if (r.converged() || !(r.final_norm > 0.0)) break;
    least[i] = r.final_norm;
  }
  try {
    system_->setOmega(current_.omega);  // back to the point the curve is at
  } catch (const std::exception&) {
    return "";
  }
  if (!std::isfinite(least[0]) || !std::isfinite(least[1])) return "";
  const double ratio = least[1] / least[0];
  if (!(ratio >= 10.0 / 3.0 && ratio <= 30.0)) return "";
  const double tangent_omega = std::abs(trial.t[n_]);
  if (tangent_omega < kCornerOmega) return "";  // a smooth fold's: not a corner
  return "the branch ends at " + at(current_.omega) +
         ": harmonic balance has no solution just past it (with omega held " + formatNumber(delta) + " and " +
         formatNumber(10.0 * delta) + " further on the solves stall at a least residual of " +
         formatNumber(least[0]) + " and " + formatNumber(least[1]) +
         ", growing in proportion to the distance), while the tangent there still points ahead (its omega-" +
         "component " + formatNumber(tangent_omega) +
         "): a corner of the curve, as where a law switches at a sample (a contact opening, a slider "
         "sticking), which the corrector, predicting ahead, cannot turn";
}

// Every point recorded, in the current system's unknowns, each bridge's
// jump left out: a bridge may land on the curve far behind the last
// points traced_ keeps (stribeck at H = 40: past its second fold, 527
// points back on the branch before the first, which it then retraced
// to the start of the range).
TracedPath ArclengthSweep::wholeCurve() const {
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
bool ArclengthSweep::switchToFullSystem() {
  const auto& steps = options_.fallbacks.steps;
  if (!system_->condensed() || std::find(steps.begin(), steps.end(), "full") == steps.end()) return false;
  if (current_.z.norm() > scaleFloor(0.0)) return false;  // a law acts: bridging is the remedy there
  const HbModel& m = system_->model();
  if ((m.structure.dofs() + m.lawComponents()) * static_cast<double>(m.basis.size()) > kMostDenseUnknowns) return false;
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

// The last way on where neither a bridge nor the full system gets past: the
// same curve sampled on twice the N from the current point. Why: the
// equality forms' kinks are sampled, and too few samples put kinks of
// their own on a branch, where the tangent flips with no fold (contact on
// the full system at H = 20, N = 1024: a turn back at 0.796 that no bridge
// crosses; on N = 2048 the curve goes through). At most twice (4 N).
bool ArclengthSweep::refineSamples() {
  if (model_.samples >= kMostSampleRefinement * scene_samples_) return false;
  HbModel finer = model_;
  finer.samples = 2 * model_.samples;
  finer.omega = current_.omega;
  std::unique_ptr<HbSystem> finer_system;
  SolverResult r;
  try {
    system_->setOmega(current_.omega);
    const Eigen::VectorXd full = system_->fullCoefficients(current_.z);
    finer_system = makeHbSystem(finer, system_->condensed(), solver_options_.linear_algebra);
    r = solver_.solve(*finer_system, finer_system->fromFullCoefficients(full), solver_options_);
  } catch (const std::exception&) {
    return false;
  }
  if (!r.converged()) return false;
  const Eigen::VectorXd& z = r.solution;
  const ArcScales s = ArcScales::at(z, std::max(kScaleFloorFraction * finer_system->unknownScale(), 1e-300), hi_ - lo_);
  // Oriented the way the curve was heading.
  const Eigen::VectorXd ahead = s.scaledDirection(current_.direction);
  Eigen::VectorXd tangent;
  if (!tangentAt(*finer_system, s, s.scaled(z, current_.omega), ahead, &tangent)) tangent = ahead.normalized();
  if (!tangent.allFinite()) return false;
  system_ = std::move(finer_system);
  model_.samples = finer.samples;
  current_ = {z, current_.omega, s.physicalDirection(tangent)};
  largest_norm_ = std::max(largest_norm_, z.norm());
  by_omega_ = false;
  traced_.clear();
  refined_.push_back("N = " + std::to_string(model_.samples) + " from omega = " + formatNumber(current_.omega));
  return true;
}

// Where the bordered Jacobian is singular at the current point (a friction
// slider stuck over the whole period leaves its mean undetermined): the
// secant to the solution with ω fixed a little further on, heading `heading`.
bool ArclengthSweep::secantTangent(const ArcScales& s, double heading, Eigen::VectorXd* tangent) {
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

// The corrector left the range between ŷ and ŷ_new: solve at the end it
// crossed with ω fixed, from the chord's point there. Accepted only near
// the chord (within one step), so that it cannot land on another branch.
// Returns whether it landed (the point recorded; at `to`, the curve complete).
bool ArclengthSweep::landOnTheEnd(const ArcScales& s, const Eigen::VectorXd& y, const Eigen::VectorXd& y_new,
                                  double step) {
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
  if (end == options_.to) finishAtTheEnd();
  return true;
}

}  // namespace eqhb::arclength
