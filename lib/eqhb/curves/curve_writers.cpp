#include "eqhb/curves/curve_writers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/io_error.h"

namespace eqhb {

CurveParts splitCurve(const Curve& curve) {
  CurveParts parts;
  for (const CurvePoint& p : curve.points) {
    parts.curve_index.push_back(p.converged ? static_cast<int>(parts.converged.size()) : -1);
    (p.converged ? parts.converged : parts.failed).push_back(&p);
  }
  return parts;
}

std::string failedCurvePath(const std::string& path) {
  const std::string csv = ".csv";
  if (path.size() > csv.size() && path.compare(path.size() - csv.size(), csv.size(), csv) == 0)
    return path.substr(0, path.size() - csv.size()) + ".failed" + csv;
  return path + ".failed.csv";
}

namespace {

// A CSV field that may hold commas or quotes (a termination with its fallbacks).
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

void writeFailedCsv(const std::string& path, const std::vector<const CurvePoint*>& failed) {
  std::ofstream out(path);
  if (!out) throwIoError(path, "cannot create the failed points' file");
  bool first = true;
  for (const char* field : kFailedPointFields) {
    out << (first ? "" : ",") << field;
    first = false;
  }
  out << "\n";
  out.precision(10);
  for (const CurvePoint* p : failed)
    out << p->omega << "," << quoted(p->termination) << "," << p->iterations << "," << p->residual_evaluations << ","
        << p->jacobian_evaluations << "," << p->residual_norm << "," << p->seconds << "\n";
  out.close();
  if (!out) throwIoError(path, "cannot write the failed points' file");
}

// The failed points as runs of neighbours with the same termination, one
// line each ("failed at omega = 1.27 to 1.358, 9 points: not_progressing"),
// the first ten runs.
void writeFailedRuns(std::ostream& out, const Curve& curve) {
  const std::vector<CurvePoint>& points = curve.points;
  int lines = 0, unlisted = 0;
  for (size_t i = 0; i < points.size();) {
    if (points[i].converged) {
      ++i;
      continue;
    }
    size_t end = i + 1;
    while (end < points.size() && !points[end].converged && points[end].termination == points[i].termination) ++end;
    if (lines++ < 10) {
      out << "  failed at omega = " << points[i].omega;
      if (end - i > 1) out << " to " << points[end - 1].omega << ", " << end - i << " points";
      out << ": " << points[i].termination << "\n";
    } else {
      unlisted += static_cast<int>(end - i);
    }
    i = end;
  }
  if (unlisted) out << "  ... and " << unlisted << " more failed points\n";
}

}  // namespace

CurveColumns curveColumns(const HbModel& model) {
  std::vector<int> all(model.structure.dofs());
  for (int i = 0; i < model.structure.dofs(); ++i) all[i] = i;
  return curveColumns(model, all);
}

CurveColumns curveColumns(const HbModel& model, const std::vector<int>& shown) {
  CurveColumns columns;
  columns.dofs = shown;
  for (int dof : shown) columns.labels.push_back(dofLabel(model, dof));
  return columns;
}

void writeCurveCsv(const std::string& path, const Curve& curve, int dofs) {
  CurveColumns columns;
  for (int i = 0; i < dofs; ++i) {
    columns.dofs.push_back(i);
    columns.labels.push_back(dofLabel(i));
  }
  writeCurveCsv(path, curve, columns);
}

void writeCurveCsv(const std::string& path, const Curve& curve, const CurveColumns& columns) {
  const CurveParts parts = splitCurve(curve);
  std::ofstream out(path);
  if (!out) throwIoError(path, "cannot create the curve file");
  out << "omega,converged,termination,iterations,residual_evaluations,jacobian_evaluations,seconds";
  for (const std::string& label : columns.labels) out << ",max_abs_" << label;
  for (const std::string& label : columns.labels) out << ",first_harmonic_" << label;
  bool with_stability = false, with_estimate = false, with_accuracy = false, with_fallback = false;
  for (const CurvePoint* p : parts.converged) {
    with_stability = with_stability || p->stable.has_value();
    with_estimate = with_estimate || p->error_estimate.has_value();
    with_accuracy = with_accuracy || p->accuracy.has_value();
    with_fallback = with_fallback || !p->fallback.empty();
  }
  out << ",energy,fold" << (with_stability ? ",stable,bifurcation" : "") << (with_estimate ? ",error_estimate" : "")
      << (with_accuracy ? ",harmonics,samples,accuracy_met,accuracy_seconds" : "")
      << (with_fallback ? ",fallback" : "") << "\n";
  out.precision(10);
  for (const CurvePoint* point : parts.converged) {
    const CurvePoint& p = *point;
    out << p.omega << ",true," << p.termination << "," << p.iterations << "," << p.residual_evaluations << ","
        << p.jacobian_evaluations << "," << p.seconds;
    for (int i : columns.dofs) out << "," << p.max_abs[i];
    for (int i : columns.dofs) out << "," << p.first_harmonic[i];
    out << "," << p.energy << "," << (p.fold ? "true" : "false");
    if (with_stability) out << "," << (p.stable ? (*p.stable ? "1" : "0") : "") << "," << p.bifurcation;
    // A point whose solve at 2H failed has no estimate: nan, as the column is numeric.
    if (with_estimate) out << "," << p.error_estimate.value_or(NAN);
    if (with_accuracy)
      out << "," << p.harmonics << "," << p.samples << "," << (p.accuracy ? (p.accuracy->met ? "1" : "0") : "")
          << "," << (p.accuracy ? p.accuracy->seconds : 0.0);
    if (with_fallback) out << "," << p.fallback;
    out << "\n";
  }
  out.close();
  if (!out) throwIoError(path, "cannot write the curve file");
  const std::string failed_path = failedCurvePath(path);
  if (!parts.failed.empty()) writeFailedCsv(failed_path, parts.failed);
  else std::remove(failed_path.c_str());  // a previous run's list would describe another curve
}

void writeCurveSummary(std::ostream& out, const Curve& curve, const CurveRun& s) {
  const CurveParts parts = splitCurve(curve);
  const int at = s.peak_dof >= 0 ? s.peak_dof : s.model->structure.dofs() - 1;
  const CurvePoint* peak = nullptr;
  for (const CurvePoint* p : parts.converged)
    if (!peak || p->max_abs[at] > peak->max_abs[at]) peak = p;
  out << s.scene << ": " << (s.arclength ? "arclength" : "sequential") << " sweep " << s.from << " -> " << s.to
      << " with " << s.solver << ", H = " << s.model->basis.count() << ": " << curve.points.size() << " points, "
      << curve.failed_points << " failed, " << curve.seconds << " s\n"
      << "  stop: " << curve.stop_reason << "\n";
  if (!curve.complete)
    for (const std::string& advice : s.advice) out << "  " << advice << "\n";
  writeFailedRuns(out, curve);
  if (peak) out << "  peak: omega = " << peak->omega << ", max|" << dofLabel(*s.model, at) << "| = " << peak->max_abs[at] << "\n";
  if (!curve.fold_omegas.empty()) {
    out << "  folds at omega =";
    for (double f : curve.fold_omegas) out << " " << f;
    out << "\n";
  } else if (s.arclength) {
    out << "  no fold\n";
  }
  if (!s.accuracy.empty()) {
    out << "  " << s.accuracy << "\n";
  } else if (s.error_estimate) {
    double worst = 0.0;
    int missing = 0;
    for (const CurvePoint* p : parts.converged) {
      if (!p->error_estimate) ++missing;
      else worst = std::max(worst, *p->error_estimate);
    }
    out << "  largest estimated relative error of max|x|: " << worst
        << (missing ? " (" + std::to_string(missing) + " points without an estimate: the solve at 2H failed)" : "")
        << "\n";
  }
  if (s.stability) {
    int stable = 0, analysed = 0;
    for (const CurvePoint* p : parts.converged) {
      analysed += p->stable.has_value();
      stable += p->stable.value_or(false);
    }
    const CurveStability& st = *s.stability;
    // One method serves a whole curve (auto chooses it from the model);
    // shooting's points may fall back to another, counted by method.
    std::map<std::string, int> by_method;
    for (const HillResult& r : st.points)
      if (!r.exponents.empty() || !r.failure.empty()) ++by_method[r.method == "hill" ? "Hill" : r.method];
    std::string methods;
    for (const auto& [name, count] : by_method)
      methods += (methods.empty() ? "" : ", ") + name + (by_method.size() > 1 ? " " + std::to_string(count) : "");
    out << "  stability (" << (methods.empty() ? "Hill" : methods) << "): " << stable << " of " << analysed << " points stable, " << st.seconds << " s ("
        << (st.solve_seconds > 0 ? 100.0 * st.seconds / st.solve_seconds : 0.0) << " % of the solve time)\n";
    if (st.time_limited)
      out << "  stability: the time limit (--stability-time-limit) ran out after " << st.analysed << " of "
          << parts.converged.size() << " converged points; the rest have no verdict\n";
    for (const auto& b : st.bifurcations) out << "  " << b.kind << " at omega = " << b.omega << "\n";
  }
}

}  // namespace eqhb
