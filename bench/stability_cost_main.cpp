// eqhb-stability-cost: what a stability check costs against the solve,
// per scene and method. Each scene's curve is swept once on the defaults of
// `eqhb sweep` (its [sweep] range, no stability); then the stability of
// every converged point is analysed `--repeats` times per method, and the
// median over repeats of (stability seconds of the curve) / (solve seconds
// of the curve) is printed, with the median time per point. The timings are
// from one process on a shared machine: compare the ratios within one run.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

#include "eqhb/app/sweep.h"
#include "eqhb/stability/curve_stability.h"
#include "report_number.h"

namespace {

using namespace eqhb;

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Row {
  std::string scene, method, answered;
  int points = 0;
  double per_point_ms = NAN, ratio = NAN;
};

// The methods that answered, e.g. "monodromy 101" or "shooting 60, monodromy 41".
std::string answeredBy(const CurveStability& stability) {
  std::vector<std::pair<std::string, int>> counts;
  for (const HillResult& p : stability.points) {
    if (p.method.empty()) continue;
    auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == p.method; });
    if (it == counts.end()) counts.push_back({p.method, 1});
    else ++it->second;
  }
  std::string text;
  for (const auto& [name, count] : counts) text += (text.empty() ? "" : ", ") + name + " " + std::to_string(count);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Stability cost against the solve, per scene and method"};
  std::vector<std::string> scenes = {"friction-1d",     "coulomb-oscillator:0.3:1.5", "contact",
                                     "penalty-contact", "jenkins-1d",                 "beam-damper",
                                     "beam-damper-elastic", "lap-joint",             "beam-joint-large",
                                     "lap-joint-varying",   "blade-tip-damper"};
  std::vector<std::string> methods = {"auto"};
  int repeats = 5;
  bool arclength = false;
  app.add_option("--scenes", scenes, "Scene names in problems/ (without .toml), NAME:FROM:TO for another range");
  app.add_option("--methods", methods, "Stability methods: auto, monodromy, hill, shooting");
  app.add_option("--repeats", repeats, "Analyses of each curve per method (the median is shown)")->check(CLI::Range(1, 1000));
  app.add_flag("--arclength", arclength, "Arclength curves instead of the sequential grid");
  CLI11_PARSE(app, argc, argv);

  std::vector<Row> rows;
  for (const std::string& entry : scenes) {
    std::vector<std::string> parts;
    std::stringstream fields(entry);
    for (std::string part; std::getline(fields, part, ':');) parts.push_back(part);
    const std::string name = parts.front();
    app::SceneSettings settings;
    settings.path = std::string(EQHB_PROBLEMS_DIR) + "/" + name + ".toml";
    app::SweepOptions options;
    options.arclength = arclength;
    app::SweepResult swept;
    try {
      if (parts.size() == 3) {
        options.from = std::stod(parts[1]);
        options.to = std::stod(parts[2]);
      }
      swept = app::sweep(settings, options);
    } catch (const std::exception& e) {
      std::cerr << entry << ": " << e.what() << "\n";
      return 2;
    }
    for (const std::string& method : methods) {
      HillOptions hill;
      hill.method = method;
      std::vector<double> ratios, per_point;
      Row row;
      row.scene = name;
      row.method = method;
      for (int r = 0; r < repeats; ++r) {
        CurveStability stability;
        try {
          stability = analyseCurveStability(swept.model, swept.curve, hill);
        } catch (const std::exception& e) {
          std::cerr << entry << ", " << method << ": " << e.what() << "\n";
          return 2;
        }
        ratios.push_back(stability.seconds / std::max(stability.solve_seconds, 1e-12));
        per_point.push_back(1e3 * stability.seconds / std::max(stability.analysed, 1));
        row.points = stability.analysed;
        row.answered = answeredBy(stability);
      }
      row.ratio = median(ratios);
      row.per_point_ms = median(per_point);
      rows.push_back(row);
      std::cerr << name << " " << method << ": " << bench::reportNumber(100.0 * row.ratio, 3) << " % of the solve\n";
    }
  }
  std::cout << "| scene | method | points | answered by | stability ms/point | stability / solve |\n"
            << "|---|---|---|---|---|---|\n";
  for (const Row& r : rows)
    std::cout << "| " << r.scene << " | " << r.method << " | " << r.points << " | " << r.answered << " | "
              << bench::reportNumber(r.per_point_ms, 3) << " | " << bench::reportNumber(100.0 * r.ratio, 3) << " % |\n";
  return 0;
}
