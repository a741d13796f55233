#include "eqhb/modes/sliding_branch.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/modes/deadline_options.h"
#include "eqhb/modes/path_tracer.h"
#include "eqhb/solvers/deadline.h"

namespace eqhb {

namespace {

class SlidingDescent {
 public:
  SlidingDescent(ModeSystem& system, Solver& solver, const SolverOptions& solver_options, const BackboneOptions& o,
                 const BackboneProgress& progress, const StaticContactState* at_rest, Backbone* backbone)
      : system_(system), solver_(solver), solver_options_(solver_options), o_(o), progress_(progress),
        at_rest_(at_rest), backbone_(*backbone), s_from_(std::log(o.from)),
        grid_step_((std::log(o.to) - s_from_) / (o.points - 1)), deadline_(o.time_limit) {}

  void run() {
    std::vector<BackbonePoint> points;
    for (int i = o_.points - 1; i >= 0; --i) {
      BackbonePoint p = solveGridPoint(i);
      work_ = BackbonePoint();
      if (!p.converged) ++backbone_.failed_points;
      if (progress_) progress_(p, i);
      points.push_back(std::move(p));
    }
    std::reverse(points.begin(), points.end());
    backbone_.points = std::move(points);
  }

 private:
  double gridS(int i) const { return s_from_ + grid_step_ * i; }

  SolverOptions options() const { return withinDeadline(solver_options_, deadline_); }

  SolverResult solveAt(double s, const Eigen::VectorXd& z0) {
    system_.setAmplitude(std::exp(s));
    system_.prepareAt(z0[system_.omegaIndex()]);
    SolverResult r = solver_.solve(system_, z0, options());
    if (r.termination == Termination::kInvalidOptions) throw InputError("options: " + r.native_message);
    work_.iterations += r.iterations;
    work_.residual_evaluations += r.residual_evaluations;
    work_.jacobian_evaluations += r.jacobian_evaluations;
    work_.seconds += r.seconds;
    return r;
  }

  // The secant through the last two solutions at s; the last alone when
  // there is one, or when the secant would move ω by more than a factor 2.
  Eigen::VectorXd predictAt(double s) const {
    if (last_.empty()) return linearStart(system_, backbone_.start, std::exp(s), at_rest_);
    const auto& [s1, z1] = last_.back();
    if (last_.size() < 2) return z1;
    const auto& [s0, z0] = last_.front();
    const Eigen::VectorXd z = z1 + (z1 - z0) * ((s - s1) / (s1 - s0));
    const double ratio = z[system_.omegaIndex()] / z1[system_.omegaIndex()];
    return ratio > 0.5 && ratio < 2.0 ? z : z1;
  }

  void keep(double s, const Eigen::VectorXd& z) {
    last_.emplace_back(s, z);
    if (last_.size() > 2) last_.erase(last_.begin());
  }

  BackbonePoint failed(int i, const std::string& why) {
    BackbonePoint p = work_;
    p.amplitude = std::exp(gridS(i));
    p.termination = why;
    return p;
  }

  BackbonePoint solveGridPoint(int i) {
    const double target = gridS(i);
    if (deadline_.passed()) {
      if (backbone_.stop.why.empty())
        backbone_.stop.why = "stopped: the time limit of " + formatNumber(deadline_.seconds()) + " s was reached";
      return failed(i, backbone_.stop.why);
    }
    const double done = last_.empty() ? target : last_.back().first;
    double step = target - done, at = done;
    SolverResult r;
    for (int halvings = 0; halvings <= o_.max_halvings;) {
      const double s = step == 0.0 ? target : std::max(at + step, target);
      r = solveAt(s, predictAt(s));
      if (!r.converged()) {
        if (step == 0.0) break;  // the start itself: nothing to halve
        ++halvings;
        step *= 0.5;
        continue;
      }
      keep(s, r.solution);
      if (s <= target) break;
      at = s;
    }
    if (!r.converged()) return failed(i, terminationName(r.termination));
    BackbonePoint p = describeModePoint(system_, r.solution, std::exp(target));
    p.converged = true;
    p.termination = terminationName(r.termination);
    p.iterations = work_.iterations;
    p.residual_evaluations = work_.residual_evaluations;
    p.jacobian_evaluations = work_.jacobian_evaluations;
    p.seconds = work_.seconds;
    return p;
  }

  ModeSystem& system_;
  Solver& solver_;
  const SolverOptions& solver_options_;
  const BackboneOptions& o_;
  const BackboneProgress& progress_;
  const StaticContactState* at_rest_;
  Backbone& backbone_;
  const double s_from_, grid_step_;
  const Deadline deadline_;
  std::vector<std::pair<double, Eigen::VectorXd>> last_;  // (s, z) of the last two solutions
  BackbonePoint work_;  // solver work since the last grid point
};

}  // namespace

void traceSlidingBranch(ModeSystem& system, Solver& solver, const SolverOptions& solver_options,
                        const BackboneOptions& o, const BackboneProgress& progress,
                        const StaticContactState* at_rest, Backbone* backbone) {
  SlidingDescent(system, solver, solver_options, o, progress, at_rest, backbone).run();
}

}  // namespace eqhb
