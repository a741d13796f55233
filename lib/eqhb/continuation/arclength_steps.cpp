#include "eqhb/continuation/arclength_steps.h"

#include <algorithm>

#include "eqhb/continuation/bordered_system.h"
#include "eqhb/continuation/continuation.h"

namespace eqhb {
namespace {
// A retrace lands on the path within this many points behind the current
// one (a corrector hovering where a curve ends can take hundreds there).
constexpr double kRetraceFraction = 0.25;

double distanceToSegment(const Eigen::VectorXd& y, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::VectorXd ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((y - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (y - a - t * ab).norm();
}
}  // namespace

ArclengthStep::ArclengthStep(const ContinuationOptions& options)
    : size_(std::clamp(options.step, options.min_step, options.max_step)),
      min_(options.min_step),
      max_(options.max_step),
      target_turn_(0.5 * options.max_turn),
      target_iterations_(options.target_iterations) {}

void ArclengthStep::accept(int corrector_iterations, double turn_angle) {
  const double by_effort = static_cast<double>(target_iterations_) / std::max(1, corrector_iterations);
  const double by_turn = turn_angle > 0.0 ? target_turn_ / turn_angle : 2.0;
  size_ = std::clamp(size_ * std::clamp(std::min(by_effort, by_turn), 0.5, 2.0), min_, max_);
}

bool ArclengthStep::halve() {
  if (size_ / 2.0 < min_) return false;
  size_ /= 2.0;
  return true;
}

void KinkTest::reset() { first_step_ = first_turn_ = 0.0; }

bool KinkTest::isKink(double step, double turn_angle) {
  if (first_step_ == 0.0) {
    first_step_ = step;
    first_turn_ = turn_angle;
    return false;
  }
  if (step > first_step_ / 4.0) return false;
  if (turn_angle >= first_turn_ / 2.0) return true;
  // Smooth so far; the bend may still end in a kink (the turn falls with the
  // step, then holds): judge the next quartering against this one.
  first_step_ = step;
  first_turn_ = turn_angle;
  return false;
}

void TracedPath::add(const Eigen::VectorXd& z, double omega) {
  Eigen::VectorXd point(z.size() + 1);
  point << z, omega;
  if (!points_.empty() && points_.back().size() != point.size()) clear();  // another system's unknowns
  points_.push_back(std::move(point));
  if (points_.size() > memory_) {
    points_.pop_front();
    break_at_.clear();  // only bridges' paths are unbounded, and they never drop a point
  }
}

bool TracedPath::retraces(const ArcScales& scales, const Eigen::VectorXd& y, const Eigen::VectorXd& y_new) const {
  const double tolerance = kRetraceFraction * (y_new - y).norm();
  std::vector<Eigen::VectorXd> scaled;
  for (const Eigen::VectorXd& p : points_) {
    if (p.size() != y_new.size()) return false;
    scaled.push_back(scales.scaled(p.head(p.size() - 1), p[p.size() - 1]));
  }
  for (size_t i = 1; i < scaled.size(); ++i)
    if (std::find(break_at_.begin(), break_at_.end(), i) == break_at_.end() && distanceToSegment(y_new, scaled[i - 1], scaled[i]) <= tolerance) return true;
  return false;
}

int FoldWatch::watch(double omega_component, int index) {
  const double sign = omega_component >= 0.0 ? 1.0 : -1.0;
  if (confirmed_ == 0.0 || sign == confirmed_) {
    confirmed_ = sign;
    candidate_ = -1;
    held_ = 0;
    return -1;
  }
  if (candidate_ < 0) candidate_ = index;
  if (++held_ < confirmation_) return -1;
  const int fold = candidate_;
  confirmed_ = sign;
  candidate_ = -1;
  held_ = 0;
  return fold;
}

}  // namespace eqhb
