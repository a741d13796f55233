// eqhb-bench, the main job: on every scene, every backend and formulation
// (law form, full vs condensed) at the scene's harmonics, each solve
// repeated for a median time, with its accuracy against the time-domain
// reference and against a 4x-H solution; the backend comparison on
// friction-1d at H = 10 and 40; and the MGH comparison of the own dogleg
// with MINPACK. Writes bench.json, bench.csv, report.md into --out.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "bench_options.h"
#include "bench_progress.h"
#include "bench_report.h"
#include "bench_sections.h"
#include "bench_studies.h"
#include "compliant_study.h"
#include "scale_study.h"

namespace fs = std::filesystem;
using namespace eqhb::bench;

namespace {

// --compliant-only: compliant.md and compliant.csv.
int runCompliantOnly(const BenchOptions& options) {
  std::ofstream(options.out + "/compliant.md") << "# eqhb: compliant vs exact Signorini contact\n\n"
                                               << compliantIntroduction() << runCompliantStudy(options);
  std::cout << "compliant study: " << options.out << "/compliant.md, " << options.out << "/compliant.csv\n";
  return 0;
}

// --scale-only: scale.md and scale.csv.
int runScaleOnly(const BenchOptions& options) {
  const std::vector<ScaleRow> scale = runScaleStudy(options.quick, scaleBackends(options.quick), options.problems);
  writeScaleCsv(options.out + "/scale.csv", scale);
  std::ofstream(options.out + "/scale.md") << "# eqhb scale study\n\n" << scaleIntroduction() << scaleReport(scale);
  std::cout << "scale study: " << options.out << "/scale.md, " << options.out << "/scale.csv\n";
  return 0;
}

// 5. Scale study (its own CSV: the quick run's smallest sizes are not in
// the perf-check baseline).
std::vector<ScaleRow> runScaleSection(const BenchOptions& options) {
  ProgressLine scale_line(eqhb::cli::verbosity().progress, "bench 5/5 scale study");
  scale_line.update(-1.0, "running");
  const std::vector<ScaleRow> scale = runScaleStudy(options.quick, scaleBackends(options.quick), options.problems);
  scale_line.finish(std::to_string(scale.size()) + " cases");
  writeScaleCsv(options.out + "/scale.csv", scale);
  return scale;
}

// --scenes-only: the scene study with its advice (bench.json, bench.csv, scenes.md).
int runScenesOnly(const BenchOptions& options) {
  const SceneLists scenes = listScenes(options.problems);
  std::vector<Case> cases;
  std::vector<TruthStatus> truths;
  runSceneStudy(options, scenes.small, builtBackends(), cases, truths);
  setRatiosToDogleg(cases);
  ReportParts parts;
  parts.metadata = writeCaseData(options.out, cases);
  parts.truth_table = truthTable(truths);
  parts.advice = adviseBackends(cases);
  writeScenesReport(options, cases, parts);
  std::cout << "scene study: " << options.out << "/scenes.md, " << options.out << "/bench.json\n";
  return 0;
}

std::string joinStems(const std::vector<fs::path>& paths) {
  std::string names;
  for (const auto& path : paths) names += (names.empty() ? "" : ", ") + path.stem().string();
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  BenchOptions options;
  int exit_code = 0;
  if (!parseBenchOptions(argc, argv, options, exit_code)) return exit_code;
  fs::create_directories(options.out);
  if (options.compliant_only) return runCompliantOnly(options);
  if (options.scale_only) return runScaleOnly(options);
  if (options.scenes_only) return runScenesOnly(options);

  const SceneLists scenes = listScenes(options.problems);
  const std::vector<std::string> built = builtBackends();
  std::vector<Case> cases = runBackendStudy(options, built);
  std::vector<TruthStatus> truths;
  runSceneStudy(options, scenes.small, built, cases, truths);
  setRatiosToDogleg(cases);

  ReportParts parts;
  parts.metadata = writeCaseData(options.out, cases);
  const std::vector<FailureRow> failures = runFailureStudy(options, scenes.small, built);
  writeFailureCsv(options.out + "/failure_maps.csv", failures);
  parts.success_table = successTable(failures);
  parts.compliant_table = runCompliantStudy(options);
  parts.curve_rows = runCurves(options, scenes.small);
  parts.mgh_table = mghTable(built);
  parts.truth_table = truthTable(truths);
  parts.advice = adviseBackends(cases);
  parts.scale = runScaleSection(options);
  parts.structure_names = joinStems(scenes.structures);
  writeReport(options, cases, parts);

  std::cout << table(cases, "backends") << "\n" << table(cases, "scenes");
  std::cerr << "wrote " << options.out << "/bench.json, bench.csv, report.md\n";
  return 0;
}
