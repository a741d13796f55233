#include "eqhb/studies/study_sample.h"

#include <chrono>
#include <cstdio>

#include "eqhb/continuation/continuation.h"
#include "eqhb/curves/curve_writers.h"
#include "eqhb/error.h"
#include "eqhb/io_error.h"
#include "eqhb/scenes/scene.h"

namespace eqhb {

std::vector<std::string> sampleOverrides(const StudySettings& settings, int id) {
  std::vector<std::string> o = settings.overrides;
  for (int p = 0; p < static_cast<int>(settings.plan.parameters.size()); ++p) {
    const auto linked = sampleOverrides(settings.plan, id, p);
    o.insert(o.end(), linked.begin(), linked.end());
  }
  return o;
}

SampleWorker::SampleWorker(const StudySettings& settings, int worker)
    : settings_(settings),
      worker_(worker),
      solver_(settings.make_solver()),
      fallbacks_(settings.make_fallbacks ? settings.make_fallbacks() : nullptr) {}

SampleResult SampleWorker::run(int id) {
  const auto started = std::chrono::steady_clock::now();
  SampleResult r;
  try {
    r = compute(id);
  } catch (const IoError&) {  // the study folder, not the sample: the study stops
    throw;
  } catch (const std::exception& e) {
    r = SampleResult();
    r.reason = e.what();
  }
  r.id = id;
  r.parameters = settings_.plan.samples[id];
  r.worker = worker_;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (!r.ok) previous_peak_ = PeakState();
  previous_id_ = id;
  return r;
}

SampleResult SampleWorker::compute(int id) {
  SampleResult r;
  const Scene scene = loadScene(settings_.scene_path, sampleOverrides(settings_, id));
  if (scene.model.structure.dofs() != settings_.dofs) {
    r.reason = "the sample has " + std::to_string(scene.model.structure.dofs()) + " DOFs, the study " +
               std::to_string(settings_.dofs);
    return r;
  }
  if (settings_.mode == StudyMode::kPeak) {
    const bool neighbour = id == previous_id_ + 1 && settings_.plan.continues[id];
    PeakOptions peak_options = settings_.peak;
    peak_options.fallbacks = fallbacks_.get();
    const PeakResult peak = trackPeak(scene.model, *solver_, settings_.solver_options, peak_options,
                                      neighbour ? &previous_peak_ : nullptr);
    r.ok = peak.converged;
    r.reason = peak.reason;
    r.start = peak.start;
    r.omega = peak.omega;
    r.first_harmonic = peak.first_harmonic;
    r.max_abs = peak.max_abs;
    r.peaks = peak.peaks;
    r.solves = peak.solves;
    r.iterations = peak.iterations;
    previous_peak_ = peak.state;
    return r;
  }
  ContinuationOptions sweep;
  sweep.from = settings_.peak.from;
  sweep.to = settings_.peak.to;
  sweep.step = settings_.sweep_step;
  sweep.min_step = std::min(1e-6, sweep.step);
  sweep.max_step = std::max(1.0, sweep.step);
  sweep.condensed = settings_.peak.condensed;
  if (fallbacks_) sweep.fallbacks = *fallbacks_;
  const Curve curve = sweepSequential(scene.model, *solver_, settings_.solver_options, sweep);
  char name[64];
  std::snprintf(name, sizeof name, "curves/sample_%06d.csv", id);
  r.curve = name;
  writeCurveCsv(settings_.out_dir + "/" + name, curve, settings_.dofs);
  r.start = "sweep";
  r.ok = curve.failed_points == 0 && !curve.points.empty();
  if (!r.ok) r.reason = curve.stop_reason;
  const int dof = settings_.peak.dof;
  const CurvePoint* best = nullptr;
  for (const auto& p : curve.points) {
    ++r.solves;
    r.iterations += p.iterations;
    if (p.converged && (!best || p.first_harmonic[dof] > best->first_harmonic[dof])) best = &p;
  }
  if (best) {
    r.omega = best->omega;
    r.first_harmonic = best->first_harmonic;
    r.max_abs = best->max_abs;
  }
  return r;
}

}  // namespace eqhb
