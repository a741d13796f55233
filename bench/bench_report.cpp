#include "bench_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "bench_sections.h"
#include "compliant_study.h"
#include "run_metadata.h"

namespace eqhb::bench {

namespace {

// The rule of the backend advice.
const char* const kAdviceRule =
    "per scene, the backend that converged in the most formulations (every form of the scene's laws, "
    "condensed and full system, zero start); ties go to the lowest median time over its converged cases";

// "eqhb VERSION, commit ... (N threads), compiler type; libraries".
std::string runLine(const nlohmann::json& metadata) {
  std::string libraries;
  for (const auto& [name, version] : metadata["libraries"].items())
    libraries += (libraries.empty() ? "" : ", ") + name + " " + version.get<std::string>();
  std::ostringstream line;
  line << "eqhb " << metadata["eqhb_version"].get<std::string>() << ", commit "
       << metadata["commit"].get<std::string>() << (metadata["uncommitted_changes"].get<bool>() ? " (+ changes)" : "")
       << ", " << metadata["date"].get<std::string>() << ", " << metadata["cpu"].get<std::string>() << " ("
       << metadata["hardware_threads"].get<unsigned>() << " threads), " << metadata["compiler"].get<std::string>()
       << " " << metadata["build_type"].get<std::string>() << "; " << libraries;
  return line.str();
}

}  // namespace

nlohmann::json writeCaseData(const std::string& out, const std::vector<Case>& cases) {
  nlohmann::json json = nlohmann::json::array();
  std::ofstream csv(out + "/bench.csv");
  csv << "study,scene,solver,system,form,harmonics,converged,termination,iterations,residual_evaluations,"
         "jacobian_evaluations,residual_norm,median_seconds,repeats,ratio_to_dogleg,error_reference,error_high_h\n";
  auto num = [](double x) { return std::isnan(x) ? nlohmann::json() : nlohmann::json(x); };
  for (const Case& c : cases) {
    json.push_back({{"study", c.study}, {"scene", c.scene}, {"solver", c.solver}, {"system", c.system},
                    {"form", c.form}, {"harmonics", c.harmonics}, {"converged", c.converged},
                    {"termination", c.termination}, {"iterations", c.iterations},
                    {"residual_evaluations", c.residual_evaluations}, {"jacobian_evaluations", c.jacobian_evaluations},
                    {"residual_norm", num(c.residual_norm)}, {"median_seconds", num(c.median_seconds)},
                    {"repeats", c.repeats}, {"ratio_to_dogleg", num(c.ratio_to_dogleg)},
                    {"error_reference", num(c.error_reference)}, {"error_high_h", num(c.error_high_h)}});
    csv << c.study << "," << c.scene << "," << c.solver << "," << c.system << "," << c.form << "," << c.harmonics
        << "," << (c.converged ? "true" : "false") << "," << c.termination << "," << c.iterations << ","
        << c.residual_evaluations << "," << c.jacobian_evaluations << "," << c.residual_norm << ","
        << c.median_seconds << "," << c.repeats << "," << c.ratio_to_dogleg << "," << c.error_reference << ","
        << c.error_high_h << "\n";
  }
  const nlohmann::json metadata = runMetadata();
  std::ofstream(out + "/bench.json") << nlohmann::json{{"metadata", metadata}, {"cases", json}}.dump(2) << "\n";
  return metadata;
}

// Most formulations converged first, then the lowest median time over the
// converged cases.
Advice adviseBackends(const std::vector<Case>& cases) {
  std::ostringstream advice, in_short;
  std::map<std::string, std::map<std::string, std::pair<int, std::vector<double>>>> score;
  std::map<std::string, int> total;
  for (const Case& c : cases) {
    if (c.study != "scenes") continue;
    auto& [ok, times] = score[c.scene][c.solver];
    ok += c.converged;
    if (c.converged) times.push_back(c.median_seconds);
  }
  for (const Case& c : cases)
    if (c.study == "scenes" && c.solver == "dogleg") ++total[c.scene];
  for (const auto& [scene, by_solver] : score) {
    std::string best;
    int best_ok = -1;
    double best_time = 0.0, slowest = 0.0;
    for (const auto& [solver, data] : by_solver) {
      const double t = data.second.empty() ? INFINITY : median(data.second);
      if (!data.second.empty()) slowest = std::max(slowest, t);
      if (data.first > best_ok || (data.first == best_ok && t < best_time)) {
        best = solver;
        best_ok = data.first;
        best_time = t;
      }
    }
    advice << "- **" << scene << "**: " << best << " (converged in " << best_ok << " of " << total[scene]
           << " formulations, median " << number(best_time) << " s; the slowest converging backend's median is "
           << number(slowest / best_time) << "x)\n";
    in_short << "| " << scene << " | " << best << " | " << best_ok << "/" << total[scene] << " | "
             << number(best_time) << " |\n";
  }
  return {advice.str(), in_short.str()};
}

void writeReport(const BenchOptions& options, const std::vector<Case>& cases, const ReportParts& parts) {
  std::ofstream report(options.out + "/report.md");
  report << "# eqhb benchmark report\n\n"
         << "## Summary\n\n"
         << "What to pick for each scene (rule: " << kAdviceRule << "):\n\n"
         << "| scene | backend | formulations converged | median s |\n|---|---|---|---|\n"
         << parts.advice.summary_rows << "\nRun: " << runLine(parts.metadata) << ".\n\n"
         << "Every solve starts from a zero initial guess with tolerance ‖g‖₂ <= 1e-10; times are medians of up to "
         << options.repeats << " solves (fewer for slow cases) on this machine. Accuracy: relative L2 error over one "
         << "period of the displacements (worst DOF) against the time-domain reference (Moreau–Jean, h = "
         << options.reference_step << ") and against the same scene solved with 4x the harmonics.\n\n"
         << "## Backends on friction-1d\n\n" << table(cases, "backends")
         << "\n## Which backend for which scene\n\nThe rule: " << kAdviceRule << ".\n\n" << parts.advice.bullets
         << "\n## References of truth\n\n" << parts.truth_table
         << "\nA time run whose period-to-period change is at most " << kUsableChange
         << " is used as reference even if it has not met the 1e-7 periodicity tolerance.\n"
         << "\n## Scenes, formulations and backends\n\n" << table(cases, "scenes")
         << "\n![performance profile](performance_profile.png)\n"
         << "\n## Variants: rho and harmonics\n\nThe scene's first form with rho = 0.1 and 10, and with twice the "
         << "harmonics, on both systems.\n\n" << table(cases, "variants")
         << "\n## Failure maps\n\nSuccess over the grids of initial guesses, harmonics, rho and forcing "
         << "(failure_maps.csv, charts failure_map_SCENE.png):\n\n" << parts.success_table
         << "\n## Compliant vs exact Signorini contact\n\n" << compliantIntroduction() << parts.compliant_table
         << "\n## Frequency-response curves\n\n| scene | sequential points | failed | s | arclength points | folds | arclength stop | s |\n"
         << "|---|---|---|---|---|---|---|---|\n" << parts.curve_rows
         << "\nCharts: curve_SCENE_*.png/.svg, work_precision_SCENE.png/.svg, convergence_*.png/.svg, "
         << "micro-benchmark slopes in micro.md.\n"
         << "\n## Own dogleg vs MINPACK hybrj on the Moré–Garbow–Hillstrom problems\n\n" << parts.mgh_table
         << "\n## Scale study\n\n" << scaleIntroduction() << "Structure "
         << "scenes measured here rather than in the scene tables: "
         << (parts.structure_names.empty() ? "none" : parts.structure_names)
         << ". Data: scale.csv; chart: scale.png/.svg.\n" << scaleReport(parts.scale)
         << "\n![scale study](scale.png)\n";
}

}  // namespace eqhb::bench
