#include "eqhb/app/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

#include "eqhb/backends/default_path.h"
#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/scenes/dof_choice.h"
#include "eqhb/solvers/option_check.h"
#include "eqhb/studies/study_journal.h"
#include "eqhb/studies/study_scheduler.h"

namespace eqhb::app {

namespace {

// The common settings as overrides every sample applies before its own.
std::vector<std::string> commonOverrides(const SceneSettings& s, const Scene& scene) {
  std::vector<std::string> overrides = s.overrides;
  if (s.harmonics) overrides.push_back("harmonic_balance.harmonics=" + std::to_string(*s.harmonics));
  if (s.samples) overrides.push_back("harmonic_balance.samples=" + std::to_string(*s.samples));
  if (s.form) {
    const auto o = lawOverrides(scene.model, "form", *s.form);
    overrides.insert(overrides.end(), o.begin(), o.end());
  }
  if (s.rho) {
    const auto o = lawOverrides(scene.model, "rho", formatNumber(*s.rho));
    overrides.insert(overrides.end(), o.begin(), o.end());
  }
  if (s.formulation) {
    const auto o = lawFormulationOverrides(scene.model, *s.formulation);
    overrides.insert(overrides.end(), o.begin(), o.end());
  }
  return overrides;
}

// A path that works at neither end of its range is a wrong path (or a
// wrong range): one error. Values bad only somewhere are failed samples.
void checkVariedPaths(const StudySettings& settings, const std::vector<VariedParameter>& parameters) {
  for (const auto& p : parameters) {
    std::string why;
    for (double value : {p.from, p.to}) {
      try {
        std::vector<std::string> probe = settings.overrides;
        for (const auto& path : parameterPaths(p)) probe.push_back(path + "=" + formatNumber(value));
        eqhb::loadScene(settings.scene_path, probe);
        why.clear();
        break;
      } catch (const InputError& e) {
        why = e.what();
      }
    }
    if (!why.empty()) throwInputError("vary", p.path, "not a usable scene value: " + why);
  }
}

void resolveRange(const Scene& scene, const StudyOptions& o, StudySettings* settings) {
  if (!o.from && !scene.sweep_from) throwInputError("from", "(missing)", "the scene has no [sweep]: give from and to");
  if (!o.to && !scene.sweep_to) throwInputError("to", "(missing)", "the scene has no [sweep]: give from and to");
  PeakOptions& peak = settings->peak;
  peak.from = o.from ? *o.from : *scene.sweep_from;
  peak.to = o.to ? *o.to : *scene.sweep_to;
  peak.dof = resolveDof(scene.model, o.dof, "dof");
  peak.coarse_points = o.coarse_points;
  peak.max_peaks = o.max_peaks;
  peak.condensed = o.condensed;
  peak.validate(settings->dofs);
  if (!(o.step > 0.0) || !std::isfinite(o.step) || o.step > peak.to - peak.from)
    throwInputError("step", formatNumber(o.step), "must be in (0, to - from]");
  settings->sweep_step = o.step;
}

}  // namespace

StudySetup setupStudy(const SceneSettings& scene_settings, const StudyOptions& o) {
  if (o.mode != "peak" && o.mode != "sweep")
    throwInputError("mode", o.mode.empty() ? "(none)" : "\"" + o.mode + "\"", "must be peak or sweep");
  if (scene_settings.document || scene_settings.path.empty())
    throwInputError("scene", "(in memory)", "a study reloads its scene per sample: give a scene file");
  std::vector<VariedParameter> parameters;
  for (const auto& v : o.vary) parameters.push_back(parseVariedParameter(v, !o.lhs));
  StudySetup setup;
  StudySettings& settings = setup.settings;
  settings.plan = o.lhs ? makeLatinHypercubePlan(parameters, *o.lhs, o.seed) : makeGridPlan(parameters);
  // The scene with the common settings; the first sample's values checked
  // here so that a wrong path is one error, not a failed row per sample.
  const Scene scene = loadScene(scene_settings);
  setup.scene_name = scene.name;
  settings.scene_path = scene_settings.path;
  settings.overrides = commonOverrides(scene_settings, scene);
  settings.dofs = scene.model.structure.dofs();
  for (int i = 0; i < settings.dofs; ++i) settings.dof_labels.push_back(dofLabel(scene.model, i));
  checkVariedPaths(settings, parameters);
  settings.mode = o.mode == "sweep" ? StudyMode::kSweep : StudyMode::kPeak;
  resolveRange(scene, o, &settings);
  settings.csv_dofs = scene.output.shown;
  if (std::find(settings.csv_dofs.begin(), settings.csv_dofs.end(), settings.peak.dof) == settings.csv_dofs.end())
    settings.csv_dofs.push_back(settings.peak.dof);
  if (o.threads < 0 || o.threads > 4096) throwInputError("threads", std::to_string(o.threads), "must be in [0, 4096]");
  std::string why;
  if (!o.solver_options.isValid(&why)) throw InputError(why);
  settings.solver_options = o.solver_options;
  // An unknown name, or options the backend refuses, is an input error now, not per sample.
  checkSolverOptions(*makeSolver(o.solver), o.solver_options);
  const std::string solver_name = o.solver;
  settings.make_solver = [solver_name] { return makeSolver(solver_name); };
  const std::string fallback = o.fallback;
  const OwnedFallbackChain checked(fallback, solver_name, "fallback");  // an unknown step is an input error now
  settings.make_fallbacks = [fallback, solver_name]() -> std::shared_ptr<const FallbackChain> {
    const auto owned = std::make_shared<OwnedFallbackChain>(fallback, solver_name, "fallback");
    return std::shared_ptr<const FallbackChain>(owned, &owned->chain());  // keeps its backends alive
  };
  settings.out_dir = o.out;
  setup.plan_text = studyPlanText(settings, o.solver);
  return setup;
}

int StudyRun::failed() const {
  int n = 0;
  for (const auto& [id, r] : rows) n += r.ok ? 0 : 1;
  return n;
}

bool StudyRun::succeeded() const { return static_cast<int>(rows.size()) == total && failed() == 0; }

StudyRun runStudy(const StudySetup& setup, int threads, const std::function<void(int done, int todo)>& finished) {
  const StudySettings& settings = setup.settings;
  StudyJournal journal(settings.out_dir, settings, setup.plan_text);
  const std::vector<int> pending = journal.pending();
  const int workers = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::vector<int> to_compute = samplesToCompute(pending, settings);
  int done = 0;
  std::mutex counting;
  const auto started = std::chrono::steady_clock::now();
  runStudyOnThreads(settings, to_compute, workers, [&](const SampleResult& r) {
    journal.append(r);  // locks
    if (!finished) return;
    const std::lock_guard<std::mutex> lock(counting);
    finished(++done, static_cast<int>(to_compute.size()));
  });
  StudyRun run;
  run.setup = setup;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  journal.writeMerged();
  run.rows = journal.done();
  run.total = static_cast<int>(settings.plan.samples.size());
  run.computed = static_cast<int>(pending.size());
  run.how = std::to_string(std::max(1, std::min(workers, run.computed))) + " thread(s)";
  return run;
}

StudyRun study(const SceneSettings& scene, const StudyOptions& options,
               const std::function<void(int done, int todo)>& finished) {
  return runStudy(setupStudy(scene, options), options.threads, finished);
}

}  // namespace eqhb::app
