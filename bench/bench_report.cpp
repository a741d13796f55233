#include "bench_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "bench_sections.h"
#include "case_verdict.h"
#include "compliant_study.h"
#include "run_metadata.h"

namespace eqhb::bench {

namespace {

// The rule of the backend advice.
const char* const kAdviceRule =
    "per scene, the backend that solved the most formulations (every form of the scene's laws, condensed and "
    "full system, zero start; solved as defined above); ties go to the lowest median time over its solved cases";

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
         "jacobian_evaluations,residual_norm,median_seconds,repeats,ratio_to_dogleg,error_reference,error_high_h,"
         "verdict\n";
  auto num = [](double x) { return std::isnan(x) ? nlohmann::json() : nlohmann::json(x); };
  for (const Case& c : cases) {
    json.push_back({{"study", c.study}, {"scene", c.scene}, {"solver", c.solver}, {"system", c.system},
                    {"form", c.form}, {"harmonics", c.harmonics}, {"converged", c.converged},
                    {"termination", c.termination}, {"iterations", c.iterations},
                    {"residual_evaluations", c.residual_evaluations}, {"jacobian_evaluations", c.jacobian_evaluations},
                    {"residual_norm", num(c.residual_norm)}, {"median_seconds", num(c.median_seconds)},
                    {"repeats", c.repeats}, {"ratio_to_dogleg", num(c.ratio_to_dogleg)},
                    {"error_reference", num(c.error_reference)}, {"error_high_h", num(c.error_high_h)},
                    {"truncation_error", num(c.truncation_error)},
                    {"verdict", verdictName(verdictOf(c))}});
    csv << csvField(c.study) << "," << csvField(c.scene) << "," << csvField(c.solver) << "," << csvField(c.system)
        << "," << csvField(c.form) << "," << c.harmonics
        << "," << (c.converged ? "true" : "false") << "," << c.termination << "," << c.iterations << ","
        << c.residual_evaluations << "," << c.jacobian_evaluations << "," << c.residual_norm << ","
        << c.median_seconds << "," << c.repeats << "," << c.ratio_to_dogleg << "," << c.error_reference << ","
        << c.error_high_h << "," << verdictName(verdictOf(c)) << "\n";
  }
  const nlohmann::json metadata = runMetadata();
  std::ofstream(out + "/bench.json") << nlohmann::json{{"metadata", metadata}, {"cases", json}}.dump(2) << "\n";
  return metadata;
}

// Most formulations solved first, then the lowest median time over the
// solved cases; a backend's converged answers that disagree with the
// references are named beside it.
Advice adviseBackends(const std::vector<Case>& cases) {
  struct Score {
    int solved = 0, disagreeing = 0, unchecked = 0;
    std::vector<double> times;
  };
  std::ostringstream advice, in_short;
  std::map<std::string, std::map<std::string, Score>> score;
  std::map<std::string, int> total;
  for (const Case& c : cases) {
    if (c.study != "scenes") continue;
    Score& s = score[c.scene][c.solver];
    const Verdict v = verdictOf(c);
    s.solved += v == Verdict::kSolved;
    s.disagreeing += v == Verdict::kDisagrees;
    s.unchecked += v == Verdict::kUnchecked;
    if (v == Verdict::kSolved) s.times.push_back(c.median_seconds);
  }
  for (const Case& c : cases)
    if (c.study == "scenes" && c.solver == "dogleg") ++total[c.scene];
  for (const auto& [scene, by_solver] : score) {
    std::string best, wrong, unchecked;  // wrong: the backends whose converged answers disagree
    int best_ok = -1;
    double best_time = 0.0, slowest = 0.0;
    for (const auto& [solver, s] : by_solver) {
      const double t = s.times.empty() ? INFINITY : median(s.times);
      if (!s.times.empty()) slowest = std::max(slowest, t);
      if (s.solved > best_ok || (s.solved == best_ok && t < best_time)) {
        best = solver;
        best_ok = s.solved;
        best_time = t;
      }
      if (s.disagreeing > 0) wrong += (wrong.empty() ? "" : ", ") + solver + " " + std::to_string(s.disagreeing);
      if (s.unchecked > 0) unchecked += (unchecked.empty() ? "" : ", ") + solver + " " + std::to_string(s.unchecked);
    }
    if (best_ok == 0) {
      const std::string why = !unchecked.empty() ? "the scene has no reference to check the answers against "
                                                   "(converged: " + unchecked + ")"
                                                 : "no backend solved a formulation";
      advice << "- **" << scene << "**: " << why << (wrong.empty() ? "" : "; converged but disagreeing with the references: " + wrong) << "\n";
      in_short << "| " << scene << " | " << (unchecked.empty() ? "none" : "unchecked") << " | 0/" << total[scene]
               << " | - |\n";
      continue;
    }
    advice << "- **" << scene << "**: " << best << " (solved " << best_ok << " of " << total[scene]
           << " formulations, median " << number(best_time) << " s; the slowest solving backend's median is "
           << number(slowest / best_time) << "x"
           << (wrong.empty() ? "" : "; converged but disagreeing with the references, counted as failures: " + wrong) << ")\n";
    in_short << "| " << scene << " | " << best << " | " << best_ok << "/" << total[scene] << " | "
             << number(best_time) << " |\n";
  }
  return {advice.str(), in_short.str()};
}

namespace {
// The summary's first lines: one default, one fallback, the rule behind them.
std::string defaultAndFallback(const std::vector<Case>& cases) {
  const DefaultChoice choice = chooseDefault(cases);
  std::ostringstream text;
  if (choice.default_backend.empty() || choice.cases == 0) return "No scene case could be checked against a reference.\n\n";
  text << "**Default: " << choice.default_backend << "**, solving " << choice.default_solved << " of "
       << choice.cases << " scene cases that have a reference (" << choice.default_disagreements
       << " converged answers that disagree with the references). ";
  if (choice.fallback_backend.empty())
    text << "No other backend solves a case it does not.";
  else
    text << "**Fallback: " << choice.fallback_backend << "**: with it, " << choice.either_solved << " of "
         << choice.cases << " are solved.";
  text << " Rule: the default solves the most cases, ties going to the lowest geometric mean time over the cases "
          "it solves; the fallback solves the most of the cases the default does not. "
       << "What counts as solved: " << verdictRule() << ".\n\n";
  return text.str();
}
}  // namespace

void writeReport(const BenchOptions& options, const std::vector<Case>& cases, const ReportParts& parts) {
  std::ofstream report(options.out + "/report.md");
  report << "# eqhb benchmark report\n\n"
         << "## Summary\n\n" << defaultAndFallback(cases)
         << "What to pick for each scene (rule: " << kAdviceRule << "):\n\n"
         << "| scene | backend | formulations solved | median s |\n|---|---|---|---|\n"
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
         << "\n## Frequency-response curves\n\nA sweep counts as done only if it covers its range with every point "
         << "converged; an incomplete one is a failure, whatever it drew.\n\n"
         << "| scene | sequential | points | failed | s | arclength | points | folds | arclength stop | s |\n"
         << "|---|---|---|---|---|---|---|---|---|---|\n" << parts.curve_rows
         << "\nCharts: curve_SCENE_*.png/.svg, work_precision_SCENE.png/.svg, convergence_*.png/.svg, "
         << "micro-benchmark slopes in micro.md.\n"
         << "\n## Own dogleg vs MINPACK hybrj on the Moré–Garbow–Hillstrom problems\n\n" << parts.mgh_table
         << "\n## Scale study\n\n" << scaleIntroduction() << "Structure "
         << "scenes measured here rather than in the scene tables: "
         << (parts.structure_names.empty() ? "none" : parts.structure_names)
         << ". Data: scale.csv; chart: scale.png/.svg.\n" << scaleReport(parts.scale)
         << "\n![scale study](scale.png)\n";
}

void writeScenesReport(const BenchOptions& options, const std::vector<Case>& cases, const ReportParts& parts) {
  std::ofstream(options.out + "/scenes.md")
      << "# eqhb scene study\n\n" << defaultAndFallback(cases) << "| scene | backend | formulations solved | median s |\n"
      << "|---|---|---|---|\n" << parts.advice.summary_rows << "\nRun: " << runLine(parts.metadata) << ".\n\n"
      << "## Which backend for which scene\n\nThe rule: " << kAdviceRule << ".\n\n" << parts.advice.bullets
      << "\n## References of truth\n\n" << parts.truth_table << "\n## Scenes, formulations and backends\n\n"
      << table(cases, "scenes");
}

}  // namespace eqhb::bench
