// The record of an arclength sweep (arclength_sweep.h): the scales of each
// step, the points with their folds, and why the sweep stopped.
#include <algorithm>
#include <cmath>

#include "eqhb/continuation/arclength_sweep.h"
#include "eqhb/continuation/unresolved_note.h"
#include "eqhb/error.h"

namespace eqhb::arclength {

ArcScales ArclengthSweep::scales() const { return ArcScales::at(current_.z, scaleFloor(0.0), hi_ - lo_); }

double ArclengthSweep::scaleFloor(double also) const {
  return std::max(kScaleFloorFraction * std::max({largest_norm_, also, unknown_scale_}), 1e-300);
}

void ArclengthSweep::record(const ArcPoint& point, const SolverResult& r, double tangent_omega,
                            const std::string& fallback) {
  model_.omega = point.omega;
  CurvePoint p = describePoint(model_, system_->fullCoefficients(point.z));
  addSolverCounts(r, &p);
  if (model_.samples != scene_samples_) p.samples = model_.samples;
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

void ArclengthSweep::finishAtTheEnd() {
  curve_.complete = true;
  stop("reached the end of the range, " + at(options_.to));
}

std::string ArclengthSweep::unresolvedAlongTheCurve() const {
  std::vector<const CurvePoint*> points;
  for (const CurvePoint& p : curve_.points) points.push_back(&p);
  return unresolvedForceClause(model_, points);
}

void ArclengthSweep::stop(const std::string& reason) {
  curve_.stop_reason = reason;
  if (!full_from_.empty()) curve_.stop_reason += " (on the full system from omega = " + full_from_ + ")";
  for (const std::string& refined : refined_) curve_.stop_reason += " (on " + refined + ")";
  if (bridged_.empty()) return;
  curve_.stop_reason += " (" + std::to_string(bridged_.size()) + " bridge(s), the curve not traced between: ";
  for (size_t i = 0; i < bridged_.size(); ++i) curve_.stop_reason += (i ? ", " : "") + bridged_[i];
  curve_.stop_reason += ")";
}

}  // namespace eqhb::arclength
