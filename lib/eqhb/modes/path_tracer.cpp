#include "eqhb/modes/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/modes/deadline_options.h"
#include "eqhb/modes/mode_path_system.h"
#include "eqhb/preload/operating_point.h"
#include "eqhb/solvers/deadline.h"

namespace eqhb {

// The laws' forces of the start are those that supply A₁(ω, ξ) x̂
// (lawForcesFor: a held DOF's support force, a spring's force).
Eigen::VectorXd linearStart(const ModeSystem& system, const LinearMode& mode, double a,
                            const StaticContactState* at_rest) {
  const HbModel& model = system.model();
  const int n = model.structure.dofs(), nb = model.basis.size();
  int fundamental = 0;
  for (size_t h = 0; h < model.basis.harmonics().size(); ++h)
    if (model.basis.harmonics()[h] == 1) fundamental = model.basis.offset(static_cast<int>(h));
  const int coefficients = (n + model.lawComponents()) * nb;  // the full system's [x̂; λ̂]
  Eigen::VectorXd z = Eigen::VectorXd::Zero(coefficients + 2);
  for (int i = 0; i < n; ++i) z[i * nb + fundamental] = a * mode.shape[i];
  const double w = mode.omega, xi = 2.0 * mode.damping_ratio * mode.omega;
  const LinearStructure& s = model.structure;
  const Eigen::VectorXd x = a * mode.shape;
  const Eigen::VectorXd cos_forces = lawForcesFor(model, s.stiffness * x - w * w * (s.mass * x));
  const Eigen::VectorXd sin_forces = lawForcesFor(model, -w * (s.damping * x - xi * (s.mass * x)));
  for (int c = 0; c < cos_forces.size(); ++c) {
    z[(n + c) * nb + fundamental] = cos_forces[c];
    z[(n + c) * nb + fundamental + 1] = sin_forces[c];
  }
  if (at_rest) z.head(coefficients) += operatingPoint(model, *at_rest);
  z[coefficients] = w;
  z[coefficients + 1] = xi;
  return system.fromFullPoint(z);
}

namespace {

// Solves the mode system at amplitude `a` from `z0`; throws InputError when
// the solver rejects its options.
SolverResult solveAt(ModeSystem& system, Solver& solver, const SolverOptions& options, double a,
                     const Eigen::VectorXd& z0) {
  system.setAmplitude(a);
  system.prepareAt(z0[system.omegaIndex()]);
  SolverResult r = solver.solve(system, z0, options);
  if (r.termination == Termination::kInvalidOptions) throw InputError("options: " + r.native_message);
  return r;
}

// Follows the mode's path in pseudo-arclength (mode_path_system.h) from a
// solution at the first grid amplitude, and records the mode at every grid
// amplitude the path crosses, in the order it crosses them: where the
// backbone folds, an amplitude between its folds is crossed three times.
// A step whose corrector fails is halved, up to max_halvings times in a
// row; the path stops there, or after turning back below `from`, and the
// grid amplitudes it did not reach are stepped to in amplitude.
class PathTracer {
 public:
  PathTracer(ModeSystem& system, Solver& solver, const SolverOptions& solver_options, const BackboneOptions& o,
             const BackboneProgress& progress, const StaticContactState* at_rest, Backbone* backbone)
      : at_rest_(at_rest),
        system_(system),
        path_(system, at_rest ? system.fromFullCoefficients(operatingPoint(system.model(), *at_rest)) : Eigen::VectorXd()),
        solver_(solver),
        solver_options_(solver_options),
        o_(o),
        progress_(progress), backbone_(*backbone), s_from_(std::log(o.from)), s_to_(std::log(o.to)),
        grid_step_((s_to_ - s_from_) / (o.points - 1)),
        deadline_(o.time_limit) {}

  void run() {
    const int first = startingPoint();
    if (first < 0) return;
    reached_ = first;
    // The secant through the last two path points is the direction of the
    // next step (from the first point: onwards in amplitude alone, as the
    // linear mode grows). A secant, not the Jacobian's null direction: at a
    // switch between stick and slip the path has a corner, where a tangent
    // from one side points off the path.
    direction_ = Eigen::VectorXd::Zero(path_.size());
    direction_[path_.sIndex()] = grid_step_;
    std::string stop;
    int halvings = 0;
    for (int taken = 0; reached_ < o_.points - 1; ++taken) {
      if (deadline_.passed()) {
        stop = timeLimitReached();
        break;
      }
      if (taken >= kMaxStepsPerPoint * o_.points) {
        stop = "stopped after " + std::to_string(taken) + " arclength steps";
        break;
      }
      const Eigen::VectorXd z = path_.modePoint(y_);
      const PathWeights weights = PathWeights::at(system_, y_, kOmegaUnit * z[system_.omegaIndex()], grid_step_);
      const Eigen::VectorXd tangent = direction_ / weights.norm(direction_);
      if (landOnGrid(weights, tangent)) {
        halvings = 0;
        continue;
      }
      const SolverResult r = correct(weights, tangent, y_ + step_ * tangent);
      if (!r.converged()) {
        if (++halvings > o_.max_halvings) {
          stop = std::string("stopped: ") + terminationName(r.termination) + " at the smallest arclength step";
          break;
        }
        step_ *= 0.5;
        continue;
      }
      halvings = 0;
      adaptStep(r);
      reached_ = std::max(reached_, recordCrossings(y_, r.solution));
      advance(weights, r.solution);
      if (y_[path_.sIndex()] < s_from_ - grid_step_) {
        stop = "stopped: the path turns back below from";
        break;
      }
    }
    if (!stop.empty()) {
      const Eigen::VectorXd z = path_.modePoint(y_);
      backbone_.stop = {stop, std::exp(y_[path_.sIndex()]), z[system_.omegaIndex()],
                        z[system_.xiIndex()] / (2.0 * z[system_.omegaIndex()])};
    }
    stepInAmplitude();
  }

 private:
  static constexpr int kMaxStepsPerPoint = 40, kEasyCorrector = 3, kHardCorrector = 8;
  // Below this a step is shrunk only by failing (the halvings count them).
  static constexpr double kSmallestStep = 1.0 / 64.0;
  // A unit of path in ω and ξ: this fraction of the current ω.
  static constexpr double kOmegaUnit = 0.05;
  // A step landed on a grid amplitude is kept when its solution is within
  // this fraction of the step from where the secant put it: farther, it may
  // have jumped to another branch (as near a fold).
  static constexpr double kLandingTolerance = 0.5;

  // Where the next grid amplitude along the secant is within the step,
  // solves there with the amplitude fixed: the grid point and the next path
  // point in one solve. False when there is none, or the solve fails or
  // lands far from the secant (an arclength step follows).
  bool landOnGrid(const PathWeights& weights, const Eigen::VectorXd& tangent) {
    const int si = path_.sIndex();
    const double s = y_[si], ts = tangent[si];
    int next = -1;
    for (int i = 0; i < o_.points; ++i)
      if (ts > 0.0 ? gridS(i) > s : gridS(i) < s) {
        if (ts > 0.0) {
          next = i;
          break;
        }
        next = i;
      }
    if (next < 0 || ts == 0.0) return false;
    const double land = (gridS(next) - s) / ts;
    if (!(land <= step_)) return false;
    const Eigen::VectorXd predicted = y_ + land * tangent;
    const double a = std::exp(gridS(next));
    const SolverResult r = solveAt(system_, solver_, options(), a, path_.modePoint(predicted));
    addWork(r);
    if (!r.converged()) return false;
    Eigen::VectorXd reached_point = path_.pathPoint(r.solution, a);
    reached_point[si] = gridS(next);  // exactly, not log(exp(s)): the next steps start at this grid point
    if (weights.norm(reached_point - predicted) > kLandingTolerance * land) return false;
    record(next, r, a);
    if (ts > 0.0) reached_ = std::max(reached_, next);
    adaptStep(r);
    advance(weights, reached_point);
    return true;
  }

  void adaptStep(const SolverResult& r) {
    if (r.iterations <= kEasyCorrector) step_ = std::min(1.0, 1.5 * step_);
    if (r.iterations >= kHardCorrector) step_ = std::max(kSmallestStep, 0.5 * step_);
  }

  // Moves to the path point `next`; a turn in amplitude is a fold.
  void advance(const PathWeights& weights, const Eigen::VectorXd& next) {
    const Eigen::VectorXd moved = next - y_;
    if (moved[path_.sIndex()] * direction_[path_.sIndex()] < 0.0) recordFold(weights, next);
    previous_ = y_;
    y_ = next;
    if (weights.norm(moved) > 0.0) direction_ = moved;
  }

  // The turn between the previous point, y_ and `next`: the extremum of
  // the quadratic in path length through their s, each unknown taken on
  // its quadratic there (at y_ itself when there is no previous point).
  void recordFold(const PathWeights& weights, const Eigen::VectorXd& next) {
    Eigen::VectorXd turn = y_;
    if (previous_.size() == y_.size()) {
      const int si = path_.sIndex();
      const double l1 = weights.norm(y_ - previous_), l2 = l1 + weights.norm(next - y_);
      // Lagrange weights on the nodes 0, l1, l2.
      auto at = [&](double l) {
        return Eigen::Vector3d((l - l1) * (l - l2) / (l1 * l2), l * (l - l2) / (l1 * (l1 - l2)),
                               l * (l - l1) / (l2 * (l2 - l1)));
      };
      // s(l) = c0 + c1 l + c2 l²: from the divided differences.
      const double d1 = (y_[si] - previous_[si]) / l1, d2 = (next[si] - y_[si]) / (l2 - l1);
      const double c2 = (d2 - d1) / l2, c1 = d1 - c2 * l1;
      const double vertex = c2 != 0.0 ? -c1 / (2.0 * c2) : l1;
      if (l1 > 0.0 && l2 > l1 && vertex > 0.0 && vertex < l2) {
        const Eigen::Vector3d w = at(vertex);
        turn = w[0] * previous_ + w[1] * y_ + w[2] * next;
      }
    }
    const Eigen::VectorXd z = path_.modePoint(turn);
    backbone_.folds.push_back({std::exp(turn[path_.sIndex()]), z[system_.omegaIndex()],
                               z[system_.xiIndex()] / (2.0 * z[system_.omegaIndex()])});
  }

  double gridS(int i) const { return s_from_ + grid_step_ * i; }

  SolverOptions options() const { return withinDeadline(solver_options_, deadline_); }

  std::string timeLimitReached() const {
    return "stopped: the time limit of " + formatNumber(deadline_.seconds()) + " s was reached";
  }

  void addWork(const SolverResult& r) {
    work_.iterations += r.iterations;
    work_.residual_evaluations += r.residual_evaluations;
    work_.jacobian_evaluations += r.jacobian_evaluations;
    work_.seconds += r.seconds;
  }

  // The first grid amplitude whose solve from the linear mode converges
  // (the ones before it failed); -1 if none does.
  int startingPoint() {
    for (int i = 0; i < o_.points; ++i) {
      if (deadline_.passed()) {
        backbone_.stop.why = timeLimitReached();
        for (; i < o_.points; ++i) recordFailed(i, backbone_.stop.why);
        return -1;
      }
      const double a = std::exp(gridS(i));
      const SolverResult r = solveAt(system_, solver_, options(), a, linearStart(system_, backbone_.start, a, at_rest_));
      addWork(r);
      if (r.converged()) {
        record(i, r, a);
        y_ = path_.pathPoint(r.solution, a);
        y_[path_.sIndex()] = gridS(i);
        return i;
      }
      recordFailed(i, terminationName(r.termination));
    }
    return -1;
  }

  SolverResult correct(const PathWeights& weights, const Eigen::VectorXd& tangent, const Eigen::VectorXd& predicted) {
    const Eigen::VectorXd z = path_.modePoint(predicted);
    system_.setAmplitude(std::exp(predicted[path_.sIndex()]));
    system_.prepareAt(z[system_.omegaIndex()]);
    path_.setConstraint(weights, tangent, predicted);
    SolverResult r = solver_.solve(path_, predicted, options());
    if (r.termination == Termination::kInvalidOptions) throw InputError("options: " + r.native_message);
    addWork(r);
    return r;
  }

  // Solves at every grid amplitude between `from` and `to` (two path
  // points), in the order the path meets them, from the chord between them;
  // returns the highest grid index crossed upwards, or -1.
  int recordCrossings(const Eigen::VectorXd& from, const Eigen::VectorXd& to) {
    const int s = path_.sIndex();
    const double s0 = from[s], s1 = to[s];
    std::vector<int> crossed;
    for (int i = 0; i < o_.points; ++i)
      if ((s0 < gridS(i) && gridS(i) <= s1) || (s1 <= gridS(i) && gridS(i) < s0)) crossed.push_back(i);
    if (s1 < s0) std::reverse(crossed.begin(), crossed.end());
    int highest = -1;
    for (int i : crossed) {
      const double a = std::exp(gridS(i));
      const Eigen::VectorXd guess = path_.modePoint(from + (to - from) * ((gridS(i) - s0) / (s1 - s0)));
      const SolverResult r = solveAt(system_, solver_, options(), a, guess);
      addWork(r);
      if (r.converged())
        record(i, r, a);
      else
        recordFailed(i, terminationName(r.termination));
      if (s1 > s0) highest = i;
    }
    return highest;
  }

  // The grid amplitudes a stopped path did not reach, each solved with the
  // amplitude fixed from the secant through the last two highest points (a
  // path can end where it turns onto another family of modes, as at an
  // internal resonance, while the backbone goes on above). A failed solve is
  // retried through intermediate amplitudes, halving the step up to
  // max_halvings times.
  void stepInAmplitude() {
    for (int i = reached_ + 1; i < o_.points; ++i) {
      if (highest_.empty() || deadline_.passed()) {
        if (deadline_.passed() && backbone_.stop.why.empty()) backbone_.stop.why = timeLimitReached();
        recordFailed(i, backbone_.stop.why);
        continue;
      }
      double done = highest_.back().first, step = gridS(i) - done;
      SolverResult r;
      for (int halvings = 0; halvings <= o_.max_halvings;) {
        const double s = std::min(done + step, gridS(i));
        r = solveAt(system_, solver_, options(), std::exp(s), secantAt(s));
        addWork(r);
        if (!r.converged()) {
          ++halvings;
          step *= 0.5;
          continue;
        }
        if (s >= gridS(i)) break;
        keepHighest(s, r.solution);
        done = s;
      }
      if (r.converged())
        record(i, r, std::exp(gridS(i)));
      else
        recordFailed(i, terminationName(r.termination));
    }
  }

  // The secant through the last two of `highest_` at s; the last alone
  // when there is one, or when the secant would move ω by more than a
  // factor 2 (across the onset of slip, where ω turns sharply).
  Eigen::VectorXd secantAt(double s) const {
    const Eigen::VectorXd& z1 = highest_.back().second;
    if (highest_.size() < 2) return z1;
    const auto& [s0, z0] = highest_.front();
    const double s1 = highest_.back().first;
    const Eigen::VectorXd z = z1 + (z1 - z0) * ((s - s1) / (s1 - s0));
    const double ratio = z[system_.omegaIndex()] / z1[system_.omegaIndex()];
    return ratio > 0.5 && ratio < 2.0 ? z : z1;
  }

  void keepHighest(double s, const Eigen::VectorXd& z) {
    highest_.emplace_back(s, z);
    if (highest_.size() > 2) highest_.erase(highest_.begin());
  }

  void record(int index, const SolverResult& r, double a) {
    if (index > highest_index_) {
      highest_index_ = index;
      keepHighest(gridS(index), r.solution);
    }
    BackbonePoint point = describeModePoint(system_, r.solution, a);
    point.converged = true;
    point.termination = terminationName(r.termination);
    push(point, index);
  }

  void recordFailed(int index, const std::string& why) {
    BackbonePoint point;
    point.amplitude = std::exp(gridS(index));
    point.termination = why;
    ++backbone_.failed_points;
    push(point, index);
  }

  void push(BackbonePoint point, int index) {
    point.iterations = work_.iterations;
    point.residual_evaluations = work_.residual_evaluations;
    point.jacobian_evaluations = work_.jacobian_evaluations;
    point.seconds = work_.seconds;
    work_ = BackbonePoint();
    backbone_.points.push_back(point);
    if (progress_) progress_(backbone_.points.back(), index);
  }


  const StaticContactState* at_rest_;
  ModeSystem& system_;
  ModePathSystem path_;
  Solver& solver_;
  const SolverOptions& solver_options_;
  const BackboneOptions& o_;
  const BackboneProgress& progress_;
  Backbone& backbone_;
  const double s_from_, s_to_, grid_step_;
  const Deadline deadline_;  // of the whole backbone (BackboneOptions::time_limit)
  Eigen::VectorXd y_;          // the last path point
  Eigen::VectorXd previous_;   // the one before
  Eigen::VectorXd direction_;  // of the last step
  double step_ = 1.0;          // of the next arclength step, in path units
  int reached_ = -1;           // the highest grid index recorded on the way up
  int highest_index_ = -1;     // of the grid points recorded, the highest
  std::vector<std::pair<double, Eigen::VectorXd>> highest_;  // (s, z) at the last two highest
  BackbonePoint work_;  // solver work since the last recorded point
};

}  // namespace

BackbonePoint describeModePoint(const ModeSystem& system, const Eigen::VectorXd& z, double a) {
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

void tracePath(ModeSystem& system, Solver& solver, const SolverOptions& solver_options, const BackboneOptions& o,
               const BackboneProgress& progress, const StaticContactState* at_rest, Backbone* backbone) {
  PathTracer(system, solver, solver_options, o, progress, at_rest, backbone).run();
}

}  // namespace eqhb
