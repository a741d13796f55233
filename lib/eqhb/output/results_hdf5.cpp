#include "eqhb/output/results_hdf5.h"

#include <cmath>

#include "eqhb/curves/curve_writers.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/output/hdf5_file.h"

namespace eqhb::output {

namespace {

// Per point, `n` values of `per_point(point)` row after row.
template <typename Points, typename Row>
std::vector<double> rows(const Points& points, std::size_t n, Row per_point) {
  std::vector<double> out;
  out.reserve(points.size() * n);
  for (const auto& p : points) {
    const auto& row = per_point(p);
    for (std::size_t i = 0; i < n; ++i) out.push_back(i < static_cast<std::size_t>(row.size()) ? row[i] : NAN);
  }
  return out;
}

template <typename Points, typename Value>
std::vector<double> column(const Points& points, Value value) {
  std::vector<double> out;
  for (const auto& p : points) out.push_back(value(p));
  return out;
}

void writePoints(Hdf5File& file, const CurveParts& parts, int dofs, bool stability, bool estimates) {
  const auto& points = parts.converged;
  file.group("/points");
  file.doubles("/points/omega", column(points, [](const CurvePoint* p) { return p->omega; }));
  file.doubles("/points/energy", column(points, [](const CurvePoint* p) { return p->energy; }));
  file.doubles("/points/residual_norm", column(points, [](const CurvePoint* p) { return p->residual_norm; }));
  file.doubles("/points/seconds", column(points, [](const CurvePoint* p) { return p->seconds; }));
  std::vector<std::int64_t> iterations, fold, stable;
  for (const CurvePoint* p : points) {
    iterations.push_back(p->iterations);
    fold.push_back(p->fold);
    stable.push_back(p->stable ? *p->stable : -1);
  }
  file.integers("/points/iterations", iterations);
  file.integers("/points/fold", fold);
  if (stability) file.integers("/points/stable", stable);
  if (estimates)
    file.doubles("/points/error_estimate",
                 column(points, [](const CurvePoint* p) { return p->error_estimate.value_or(NAN); }));
  const auto n = static_cast<std::size_t>(dofs);
  file.matrix("/points/max_abs", rows(points, n, [](const CurvePoint* p) { return p->max_abs; }), points.size(), n);
  file.matrix("/points/first_harmonic", rows(points, n, [](const CurvePoint* p) { return p->first_harmonic; }),
              points.size(), n);
}

}  // namespace

void writeSweepHdf5(const std::string& path, const app::SweepResult& r) {
  const HbModel& model = r.plan.scene.model;
  const Curve& curve = r.curve;
  const CurveParts parts = splitCurve(curve);
  Hdf5File file(path);
  file.attribute("/", "scene", r.plan.scene.name);
  file.attribute("/", "solver", r.plan.solver_name);
  file.attribute("/", "method", r.plan.options.arclength ? "arclength" : "sequential");
  file.attribute("/", "harmonics", model.basis.count());
  file.attribute("/", "samples", model.samples);
  file.attribute("/", "complete", curve.complete ? 1.0 : 0.0);
  file.attribute("/", "stop_reason", curve.stop_reason);
  file.attribute("/", "peak_dof", dofLabel(model, r.plan.scene.output.peak));
  file.strings("/dof_labels", curveColumns(model).labels);
  file.doubles("/folds", curve.fold_omegas);
  bool estimates = false;
  for (const CurvePoint* p : parts.converged) estimates = estimates || p->error_estimate.has_value();
  writePoints(file, parts, model.structure.dofs(), r.stability.has_value(), estimates);
  file.group("/failed");
  std::vector<std::string> terminations;
  for (const CurvePoint* p : parts.failed) terminations.push_back(p->termination);
  file.doubles("/failed/omega", column(parts.failed, [](const CurvePoint* p) { return p->omega; }));
  file.strings("/failed/termination", terminations);
  file.close();
}

void writeStudyHdf5(const std::string& path, const app::StudyRun& run) {
  const StudySettings& settings = run.setup.settings;
  Hdf5File file(path);
  file.attribute("/", "scene", run.setup.scene_name);
  file.attribute("/", "mode", settings.mode == StudyMode::kPeak ? "peak" : "sweep");
  file.attribute("/", "dof", settings.peak.dof + 1);
  std::vector<std::string> parameters, status, reasons;
  for (const auto& p : settings.plan.parameters) parameters.push_back(p.path);
  file.strings("/parameters", parameters);
  std::vector<SampleResult> samples;
  std::vector<std::int64_t> ids;
  for (const auto& [id, r] : run.rows) {
    samples.push_back(r);
    ids.push_back(id);
    status.push_back(r.ok ? "ok" : "failed");
    reasons.push_back(r.reason);
  }
  const auto n = static_cast<std::size_t>(settings.dofs);
  file.group("/samples");
  file.integers("/samples/sample", ids);
  file.matrix("/samples/values", rows(samples, parameters.size(), [](const SampleResult& r) { return r.parameters; }),
              samples.size(), parameters.size());
  file.strings("/samples/status", status);
  file.strings("/samples/reason", reasons);
  file.doubles("/samples/peak_omega", column(samples, [](const SampleResult& r) { return r.ok ? r.omega : NAN; }));
  file.matrix("/samples/first_harmonic", rows(samples, n, [](const SampleResult& r) { return r.first_harmonic; }),
              samples.size(), n);
  file.matrix("/samples/max_abs", rows(samples, n, [](const SampleResult& r) { return r.max_abs; }), samples.size(), n);
  file.close();
}

}  // namespace eqhb::output
