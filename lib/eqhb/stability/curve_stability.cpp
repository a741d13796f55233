#include "eqhb/stability/curve_stability.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "eqhb/stability/monodromy_stability.h"
#include "eqhb/stability/shooting_stability.h"

namespace eqhb {

namespace {

// The ω-direction of the tangent changes sign between points lo and hi.
bool turnsBetween(const Curve& curve, int lo, int hi) {
  double first = NAN;
  for (int i = std::max(lo, 0); i <= std::min(hi, static_cast<int>(curve.points.size()) - 1); ++i) {
    if (!curve.points[i].tangent_omega) continue;
    const double t = *curve.points[i].tangent_omega;
    if (std::isnan(first)) first = t;
    else if ((t >= 0.0) != (first >= 0.0)) return true;
  }
  return false;
}

}  // namespace

namespace {

// "auto" takes the monodromy wherever its laws allow: on friction-1d it
// costs 19 us a point against Hill's ~1.7 ms, on beam-damper (reduced to
// its law DOFs and slow modes) 0.15 ms against 24 ms, on the lap joint
// (penalty contact and Jenkins AFT between nodes, reduced to the laws'
// relative coordinates) ~5 ms against 1.8 s.
// Shooting (exact multipliers) costs 2-9 ms a point on the small scenes,
// 20-100 times their solve, so auto does not take it.
bool useMonodromy(const HbModel& model, const HillOptions& options) {
  options.validate();
  return options.method == "monodromy" || (options.method == "auto" && MonodromyStability::supports(model));
}

}  // namespace

HillResult analyseStability(const HbModel& model, const Eigen::VectorXd& full, const HillOptions& options) {
  options.validate();
  if (options.method == "shooting") return ShootingStability(model, options).analyse(model.omega, full);
  if (useMonodromy(model, options)) return MonodromyStability(model, options.unit_tolerance).analyse(model.omega, full);
  return hillStability(model, full, options);
}

CurveStability analyseCurveStability(const HbModel& model, Curve& curve, const HillOptions& options,
                                     const std::function<void(int done, int total)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  CurveStability out;
  out.points.resize(curve.points.size());
  bool has_tangents = false;
  std::unique_ptr<HillStability> hill;
  std::unique_ptr<MonodromyStability> monodromy;
  std::unique_ptr<ShootingStability> shooting;
  options.validate();
  if (options.method == "shooting") shooting = std::make_unique<ShootingStability>(model, options);
  else if (useMonodromy(model, options)) monodromy = std::make_unique<MonodromyStability>(model, options.unit_tolerance);
  else hill = std::make_unique<HillStability>(model, options);
  auto outOfTime = [&]() {
    if (options.stop_requested && options.stop_requested->load(std::memory_order_relaxed)) return true;
    return options.time_limit > 0.0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= options.time_limit;
  };
  for (size_t i = 0; i < curve.points.size(); ++i) {
    CurvePoint& p = curve.points[i];
    out.solve_seconds += p.seconds;
    has_tangents = has_tangents || p.tangent_omega.has_value();
    p.stable.reset();
    p.bifurcation.clear();
    if (!p.converged || p.full.size() == 0) continue;
    if (out.time_limited || outOfTime()) {
      out.time_limited = true;
      continue;
    }
    ++out.analysed;
    out.points[i] = shooting    ? shooting->analyse(p.omega, p.full)
                     : monodromy ? monodromy->analyse(p.omega, p.full)
                                 : hill->analyse(p.omega, p.full);
    if (out.points[i].failure.empty()) p.stable = out.points[i].stable;
    if (progress) progress(static_cast<int>(i) + 1, static_cast<int>(curve.points.size()));
  }
  std::vector<double> folds;
  int previous = -1;
  for (int i = 0; i < static_cast<int>(curve.points.size()); ++i) {
    curve.points[i].fold = false;
    if (!curve.points[i].stable) continue;
    if (previous >= 0) {
      std::string kind = bifurcationKind(out.points[previous], out.points[i], options.unit_tolerance);
      if (kind == "fold" && has_tangents && !turnsBetween(curve, previous - 1, i + 1)) kind = "branch-point";
      if (!kind.empty()) {
        const double omega = 0.5 * (curve.points[previous].omega + curve.points[i].omega);
        out.bifurcations.push_back({i, omega, kind});
        curve.points[i].bifurcation = kind;
        if (kind == "fold") {
          curve.points[i].fold = true;
          folds.push_back(omega);
        }
      }
    }
    previous = i;
  }
  curve.fold_omegas = folds;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace eqhb
