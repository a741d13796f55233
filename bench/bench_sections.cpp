#include "bench_sections.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "bench_cases.h"
#include "bench_progress.h"
#include "compliant_study.h"
#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/curves/curve_writers.h"
#include "eqhb/scenes/scene.h"
#include "mgh/mgh_problems.h"

namespace fs = std::filesystem;

namespace eqhb::bench {

std::vector<FailureRow> runFailureStudy(const BenchOptions& options, const std::vector<fs::path>& scenes,
                                        const std::vector<std::string>& built) {
  std::vector<FailureRow> failures;
  const bool quick = options.quick;
  const std::vector<std::string> map_backends =
      quick ? std::vector<std::string>{"dogleg", "dogleg-newton", "ceres-dogleg"}
            : std::vector<std::string>{"dogleg", "dogleg-newton", "minpack", "ceres-lm", "ceres-dogleg", "ipopt-ls",
                                       "nlopt-slsqp"};
  ProgressLine maps_line(cli::verbosity().progress, "bench 3/5 failure maps");
  for (const auto& path : scenes) {
    const std::string stem = path.stem().string();
    const size_t scene_index = &path - scenes.data();
    maps_line.update(static_cast<double>(scene_index) / scenes.size(), count("scene", scene_index + 1, scenes.size()),
                     stem);
    static const std::vector<std::string> mapped = {"friction-1d", "friction-2d", "contact", "cubic",
                                                    "contact-friction-2d", "jenkins-1d", "damper"};
    if (quick ? stem != "friction-1d" : std::find(mapped.begin(), mapped.end(), stem) == mapped.end()) continue;
    std::vector<std::string> available;
    for (const auto& b : map_backends)
      if (std::find(built.begin(), built.end(), b) != built.end()) available.push_back(b);
    const auto rows = failureMaps(path, available, quick);
    failures.insert(failures.end(), rows.begin(), rows.end());
  }
  maps_line.finish(std::to_string(failures.size()) + " solves");
  return failures;
}

void writeFailureCsv(const std::string& path, const std::vector<FailureRow>& rows) {
  std::ofstream f(path);
  f << "scene,grid,solver,value,seed,converged,termination,iterations,seconds\n";
  for (const auto& r : rows)
    f << r.scene << "," << r.grid << "," << r.solver << "," << r.value << "," << r.seed << ","
      << (r.converged ? "true" : "false") << "," << r.termination << "," << r.iterations << "," << r.seconds << "\n";
}

std::string successTable(const std::vector<FailureRow>& rows) {
  std::ostringstream success;
  std::map<std::string, std::pair<int, int>> rate;  // solver -> (converged, total)
  for (const auto& r : rows) {
    auto& [ok, total] = rate[r.solver];
    ok += r.converged;
    ++total;
  }
  success << "| backend | converged | cases | success rate |\n|---|---|---|---|\n";
  for (const auto& [solver, counts] : rate)
    success << "| " << solver << " | " << counts.first << " | " << counts.second << " | "
            << number(100.0 * counts.first / std::max(1, counts.second)) << " % |\n";
  return success.str();
}

std::string runCompliantStudy(const BenchOptions& options) {
  const fs::path scene = fs::path(options.problems) / "contact-friction-2d.toml";
  if (!fs::exists(scene)) return "(contact-friction-2d not in --problems)\n";
  const std::vector<double> stiffnesses = options.quick ? std::vector<double>{1.0, 1e2, 1e4, 1e6}
                                                        : std::vector<double>{1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6};
  const auto rows = compliantStudy(scene, stiffnesses);
  std::ofstream f(options.out + "/compliant.csv");
  f << "scene,system,k_n,converged,termination,iterations,residual_evaluations,seconds,distance,penetration\n";
  for (const auto& r : rows)
    f << r.scene << "," << r.system << "," << r.k_n << "," << (r.converged ? "true" : "false") << ","
      << r.termination << "," << r.iterations << "," << r.residual_evaluations << "," << r.seconds << ","
      << r.distance << "," << r.penetration << "\n";
  return compliantReport(rows);
}

std::string runCurves(const BenchOptions& options, const std::vector<fs::path>& scenes) {
  const bool quick = options.quick;
  std::ostringstream curves;
  ProgressLine curves_line(cli::verbosity().progress, "bench 4/5 curves");
  for (const auto& path : scenes) {
    const Scene scene = loadScene(path.string());
    const size_t scene_index = &path - scenes.data();
    curves_line.update(static_cast<double>(scene_index) / scenes.size(), count("scene", scene_index + 1, scenes.size()),
                       scene.name);
    if (!scene.sweep_from) continue;
    auto solver = makeSolver("dogleg");
    ContinuationOptions sweep;
    sweep.from = *scene.sweep_from;
    sweep.to = *scene.sweep_to;
    sweep.step = std::abs(sweep.to - sweep.from) / (quick ? 50 : 200);  // a sweep may run downwards
    sweep.max_points = quick ? 1500 : 6000;
    sweep.condensed = path.stem() != "contact";  // contact: only the full system starts cold
    const Curve sequential = sweepSequential(scene.model, *solver, {}, sweep);
    // The arclength on the command line's defaults: the curve a user gets.
    sweep.step = ContinuationOptions::defaultStep(sweep.from, sweep.to, true);
    sweep.min_step = ContinuationOptions::defaultMinStep(sweep.step);
    sweep.max_step = ContinuationOptions::defaultMaxStep(sweep.step);
    const Curve arclength = sweepArclength(scene.model, *solver, {}, sweep);
    const int dofs = scene.model.structure.dofs();
    writeCurveCsv(options.out + "/curve_" + scene.name + "_sequential.csv", sequential, dofs);
    writeCurveCsv(options.out + "/curve_" + scene.name + "_arclength.csv", arclength, dofs);
    // A curve that lost points or stopped short is a failure, whatever it drew.
    const bool sequential_whole = sequential.complete && sequential.failed_points == 0;
    curves << "| " << scene.name << " | " << (sequential_whole ? "complete" : "**incomplete**") << " | "
           << sequential.points.size() << " | " << sequential.failed_points << " | " << number(sequential.seconds)
           << " | " << (arclength.complete ? "complete" : "**incomplete**") << " | " << arclength.points.size() << " | "
           << arclength.fold_omegas.size() << " | " << arclength.stop_reason << " | " << number(arclength.seconds)
           << " |\n";
    note(curves_line, cat("  curves ", scene.name, ": sequential ", sequential.failed_points, " failed, arclength ",
                          arclength.stop_reason));
  }
  curves_line.finish();
  return curves.str();
}

std::string mghTable(const std::vector<std::string>& built) {
  if (std::find(built.begin(), built.end(), "minpack") == built.end()) return "(MINPACK backend not built)\n";
  auto own = makeSolver("dogleg");
  auto reference = makeSolver("minpack");
  return mgh::markdownTable(mgh::compare(*own, *reference, mgh::standardCases()));
}

std::vector<std::string> scaleBackends(bool quick) {
  if (quick) return {"dogleg"};
  return {"dogleg", "dogleg-newton", "minpack", "ceres-dogleg", "ipopt-square", "nlopt-lbfgs"};
}

std::string scaleIntroduction() {
  return "Generated chains (`eqhb generate`), friction limit 0.2, forced at the free end at omega = 0.3 (inside "
         "the pass band of every chain), solved from zero. Each case runs in its own child process: peak memory is "
         "the growth of its getrusage maximum resident set over the benchmark's own pages inherited at the fork. A "
         "backend that does not converge or takes more than 20 s at one size is not run at the larger ones. ";
}

}  // namespace eqhb::bench
