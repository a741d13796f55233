// Step-length control and fold detection of the arclength sweep, each a
// small strategy the sweep's loop consults once per attempt or point.
#pragma once

#include <deque>
#include <vector>

#include <Eigen/Dense>

namespace eqhb {

struct ArcScales;

struct ContinuationOptions;

// The scaled arclength step Δs, in [min_step, max_step]. After an accepted
// point it grows or shrinks (at most ×2, at least ×½) by the smaller of two
// ratios: the corrector's target iterations over the iterations it took,
// and the target turn (half the largest) over the angle the tangent turned.
class ArclengthStep {
 public:
  explicit ArclengthStep(const ContinuationOptions& options);
  double size() const { return size_; }
  void accept(int corrector_iterations, double turn_angle);
  // Halves the step after a rejected attempt; false (step unchanged) when
  // half would be below min_step.
  bool halve();

 private:
  double size_, min_, max_, target_turn_;
  int target_iterations_;
};

// Tells a kink of the curve (the tangent jumps: its turn does not shrink
// with the step, as on a nonsmooth law's switch) from a smooth bend that a
// shorter step resolves. Fed each rejected turn at one point.
class KinkTest {
 public:
  void reset();
  // True once the step has been quartered since the last reference (the
  // first rejection, then each quartering whose turn fell) and the turn is
  // still at least half of what it was there (smooth bends turn ∝ Δs).
  bool isKink(double step, double turn_angle);

 private:
  double first_step_ = 0.0, first_turn_ = 0.0;
};

// Folds: lasting reversals of the ω-direction of travel. On nonsmooth laws
// the direction can flicker near a fold, so a reversal counts
// only once it has held for `confirmation` points; the fold is placed at
// the point where it began.
class FoldWatch {
 public:
  explicit FoldWatch(int confirmation = 3) : confirmation_(confirmation) {}
  // The ω-direction of travel (its sign) from point `index` on; returns the
  // index where a newly confirmed reversal began (the fold), or −1.
  int watch(double omega_component, int index);
  // The confirmed direction of travel in ω (+1, −1; 0 before the first point).
  double direction() const { return confirmed_; }

 private:
  int confirmation_;
  double confirmed_ = 0.0;
  int candidate_ = -1, held_ = 0;
};

// The last points traced, to tell at a kink where the curve turns back in ω
// a nonsmooth fold (a contact closing: the point found lies on a new branch,
// away from the traced one) from a retrace (the point found lies back on the
// traced branch: the curve did not turn, the corrector went back).
class TracedPath {
 public:
  // Keeps the last `memory` points: enough to tell a retrace at a kink,
  // where the path went back a few steps; a bridge's jump asks of the whole
  // curve (unbounded).
  explicit TracedPath(size_t memory = 512) : memory_(memory) {}
  void add(const Eigen::VectorXd& z, double omega);
  // Ends the segment at the last point: the next point added starts a new
  // one (a bridge's jump is no part of the path).
  void breakPath() { break_at_.push_back(points_.size()); }
  void clear() {
    points_.clear();
    break_at_.clear();
  }
  // True when `y_new`, found from the last point `y` (both scaled by
  // `scales`), lies closer to the traced path than a quarter of its distance
  // from `y`: back on the path (a chord of a bend within max_turn is off
  // its arc by less than a sixth of that), not on a branch of its own.
  bool retraces(const ArcScales& scales, const Eigen::VectorXd& y, const Eigen::VectorXd& y_new) const;

 private:
  size_t memory_;
  std::deque<Eigen::VectorXd> points_;  // [z; ω] in physical units
  std::vector<size_t> break_at_;        // no segment from points_[i − 1] to points_[i]
};

}  // namespace eqhb
