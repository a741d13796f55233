#include "eqhb/continuation/failed_runs.h"

#include <cmath>
#include <memory>
#include <string>

#include "eqhb/continuation/unresolved_note.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

namespace {

// Arclength points to follow one branch across a run: the run spans a few
// grid steps, a branch that needs more turns there than a fold's.
constexpr int kMostArcPoints = 400;

// The branch from one converged neighbour, traced towards `toward`.
Curve traceBranch(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                  const ContinuationOptions& options, const CurvePoint& from, double toward) {
  ContinuationOptions arc = options;
  arc.from = from.omega;
  arc.to = toward;
  arc.start_full = from.full;
  arc.step = ContinuationOptions::defaultStep(arc.from, arc.to, true);
  arc.min_step = ContinuationOptions::defaultMinStep(arc.step);
  arc.max_step = ContinuationOptions::defaultMaxStep(arc.step);
  arc.max_points = kMostArcPoints;
  // No fallback: a bridge would jump off the branch whose end is sought.
  arc.fallbacks = FallbackChain{};
  try {
    return sweepArclength(model, solver, solver_options, arc);
  } catch (const std::exception& e) {
    Curve none;
    none.stop_reason = e.what();
    return none;
  }
}

// Solves grid point `point` from the branch where two consecutive arc points
// straddle its ω (their secant interpolated at it): true when it converged.
bool solveFromBranch(const HbModel& model, Solver& solver, const SolverOptions& solver_options, bool condensed,
                     const Curve& branch, double start_omega, CurvePoint* point) {
  const double omega = point->omega;
  for (size_t j = 0; j + 1 < branch.points.size(); ++j) {
    const CurvePoint& a = branch.points[j];
    const CurvePoint& b = branch.points[j + 1];
    if (!a.converged || !b.converged || (a.omega - omega) * (b.omega - omega) > 0.0 || a.omega == b.omega) continue;
    HbModel m = model;
    m.omega = omega;
    try {
      auto system = makeHbSystem(m, condensed, solver_options.linear_algebra);
      const double s = (omega - a.omega) / (b.omega - a.omega);
      const Eigen::VectorXd start = system->fromFullCoefficients(a.full + s * (b.full - a.full));
      const SolverResult r = solver.solve(*system, start, solver_options);
      addSolverCounts(r, point);
      if (!r.converged()) return false;
      point->fallback = "by arclength from omega = " + formatNumber(start_omega);
      describeInto(m, system->fullCoefficients(r.solution), point);
      return true;
    } catch (const std::exception&) {
      return false;  // ω cannot be set (a singular A_k): the point stays failed
    }
  }
  return false;
}

// Where a traced branch ended without crossing the run, in a few words:
// "from omega = 0.126 it folds back at 0.1266", or where it stops and the
// first clause of why (the arclength's stop reason, up to its advice).
std::string branchEnd(const Curve& branch, double start_omega) {
  const std::string from = "from omega = " + formatNumber(start_omega);
  if (!branch.fold_omegas.empty()) return from + " it folds back at " + formatNumber(branch.fold_omegas.front());
  const std::string why = branch.stop_reason.substr(0, branch.stop_reason.find_first_of(":;"));
  const std::string clause = why.substr(0, why.find(" near "));
  if (branch.points.empty()) return from + " it could not be followed (" + clause + ")";
  return from + " it ends at " + formatNumber(branch.points.back().omega) + " (" + clause + ")";
}

}  // namespace

void followBranchesAcrossFailedRuns(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                                    const ContinuationOptions& options, Curve* curve) {
  std::vector<CurvePoint>& points = curve->points;
  const int count = static_cast<int>(points.size());
  for (int first = 0; first < count; ++first) {
    if (points[first].converged) continue;
    int last = first;
    while (last + 1 < count && !points[last + 1].converged) ++last;
    const int before = first - 1, after = last + 1;
    std::string ends;
    int traced = 0;
    for (const int side : {before, after}) {
      if (side < 0 || side >= count || !points[side].converged || points[side].full.size() == 0) continue;
      // Towards the other neighbour, or a grid step past the run's far end.
      const int other = side == before ? after : before;
      const double far = side == before ? points[last].omega : points[first].omega;
      const double toward = other >= 0 && other < count ? points[other].omega : far + (far - points[side].omega) / (last - first + 1);
      ++traced;
      const Curve branch = traceBranch(model, solver, solver_options, options, points[side], toward);
      bool all_solved = true;
      for (int i = first; i <= last; ++i) {
        if (points[i].converged) continue;
        CurvePoint trial = points[i];
        if (solveFromBranch(model, solver, solver_options, options.condensed, branch, points[side].omega, &trial)) {
          points[i] = trial;
          --curve->failed_points;
        } else {
          all_solved = false;
          points[i].iterations = trial.iterations;  // the attempt's counts stay with the point
          points[i].residual_evaluations = trial.residual_evaluations;
          points[i].jacobian_evaluations = trial.jacobian_evaluations;
          points[i].seconds = trial.seconds;
        }
      }
      if (all_solved) break;
      ends += (ends.empty() ? "" : "; ") + branchEnd(branch, points[side].omega);
    }
    // Where the neighbours' force is not resolved, the branches' ends are
    // likely the truncation's doing: say so.
    if (!ends.empty())
      ends += unresolvedForceClause(model, {before >= 0 ? &points[before] : nullptr, after < count ? &points[after] : nullptr});
    for (int i = first; i <= last; ++i)
      if (!points[i].converged && !ends.empty())
        points[i].termination +=
            std::string(traced > 1 ? " (no solution on either neighbour's branch: " : " (no solution on the neighbour's branch: ") +
            ends + ")";
    first = last;
  }
}

}  // namespace eqhb
