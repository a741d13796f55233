// eqhb-bench: every scene × backend × system × law form × harmonics, each
// solve repeated for a median time, with its accuracy against the scene's
// highest-H solution. Writes bench.json, bench.csv and report.md into --out,
// plus the MGH comparison of the own dogleg with MINPACK.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "eqhb/coulomb_1d.h"
#include "eqhb/hb_solution.h"
#include "eqhb/hb_systems.h"
#include "eqhb/scene.h"
#include "mgh/mgh_problems.h"
#include "registry.h"

namespace fs = std::filesystem;
using namespace eqhb;

namespace {

struct Case {
  std::string scene, solver, system, form;
  int harmonics = 0;
  bool converged = false;
  std::string termination;
  int iterations = 0, residual_evaluations = 0, jacobian_evaluations = 0;
  double residual_norm = 0, median_seconds = 0, error_max_abs = NAN;
  double ratio_to_dogleg = NAN;  // median time / own dogleg's, same scene, H, form, system
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// max|x| of the last DOF carrying a law: the amplitude the user looks at.
double amplitude(const HbModel& model, const Eigen::VectorXd& full) {
  const HbSolution s = summarize(model, full);
  return s.displacements[model.laws.empty() ? 0 : model.laws.back().dofs.back()].max_abs;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"eqhb-bench: solvers x formulations x harmonics on every scene"};
  std::string problems = EQHB_PROBLEMS_DIR, out = "results";
  bool quick = false;
  int repeats = 7;
  app.add_option("--problems", problems, "Folder of scene files");
  app.add_option("--out", out, "Output folder");
  app.add_flag("--quick", quick, "Small run (default harmonics only, 3 repeats)");
  app.add_option("--repeats", repeats, "Solves per case for the median time")->check(CLI::Range(1, 1000));
  CLI11_PARSE(app, argc, argv);
  if (quick) repeats = std::min(repeats, 3);
  fs::create_directories(out);

  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(problems))
    if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());

  std::vector<Case> cases;
  for (const auto& path : scenes) {
    const Scene base = loadScene(path.string());
    const int h0 = base.model.basis.count();
    std::vector<int> harmonic_counts = {h0};
    if (!quick) harmonic_counts.push_back(4 * h0);
    // Reference: the highest H of the study, Newton-dogleg, exact min/max form.
    const int h_ref = 8 * h0;
    const Scene ref_scene = loadScene(path.string(), {"harmonic_balance.harmonics=" + std::to_string(h_ref),
                                                       "harmonic_balance.samples=4096"});
    CondensedSystem ref_system(ref_scene.model);
    SolverOptions ref_options;
    ref_options.residual_tolerance = 1e-10;
    const SolverResult ref = makeSolver("dogleg-newton")->solve(ref_system, Eigen::VectorXd::Zero(ref_system.size()), ref_options);
    const double ref_amplitude = amplitude(ref_scene.model, ref_system.fullCoefficients(ref.solution));
    std::cerr << base.name << ": reference H = " << h_ref << " " << ref.summary() << "\n";

    // The forms of the scene's first law (all its laws take the same form).
    std::vector<std::string> forms = {""};
    if (!base.model.laws.empty() && !lawForms(base.model.laws[0].law->type()).empty())
      forms = lawForms(base.model.laws[0].law->type());
    for (int h : harmonic_counts)
      for (const std::string& form : forms)
        for (const bool condensed : {true, false})
          for (const auto& entry : registeredSolvers()) {
            std::vector<std::string> set = {"harmonic_balance.harmonics=" + std::to_string(h)};
            if (!form.empty())
              for (size_t l = 0; l < base.model.laws.size(); ++l)
                if (base.model.laws[l].law->type() == base.model.laws[0].law->type())
                  set.push_back("law[" + std::to_string(l) + "].form=" + form);
            const Scene scene = loadScene(path.string(), set);
            std::unique_ptr<HbSystem> system;
            if (condensed) system = std::make_unique<CondensedSystem>(scene.model);
            else system = std::make_unique<FullSystem>(scene.model);
            auto solver = makeSolver(entry.name);
            SolverOptions options;
            options.time_limit = 10.0;
            std::vector<double> times;
            SolverResult r;
            // Repeat for a stable median, but stop repeating slow cases after ~2 s.
            double spent = 0.0;
            for (int i = 0; i < repeats && (i == 0 || spent < 2.0); ++i) {
              r = solver->solve(*system, Eigen::VectorXd::Zero(system->size()), options);
              times.push_back(r.seconds);
              spent += r.seconds;
            }
            Case c;
            c.scene = base.name;
            c.solver = entry.name;
            c.system = condensed ? "condensed" : "full";
            c.form = form.empty() ? "-" : form;
            c.harmonics = h;
            c.converged = r.converged();
            c.termination = terminationName(r.termination);
            c.iterations = r.iterations;
            c.residual_evaluations = r.residual_evaluations;
            c.jacobian_evaluations = r.jacobian_evaluations;
            c.residual_norm = r.final_norm;
            c.median_seconds = median(times);
            if (c.converged)
              c.error_max_abs = std::abs(amplitude(scene.model, system->fullCoefficients(r.solution)) - ref_amplitude) /
                                std::abs(ref_amplitude);
            cases.push_back(c);
            std::cerr << "  " << c.scene << " H=" << h << " " << c.form << " " << c.system << " " << c.solver
                      << ": " << c.termination << " " << c.median_seconds << " s\n";
          }
  }

  for (Case& c : cases)
    for (const Case& d : cases)
      if (d.solver == "dogleg" && d.scene == c.scene && d.harmonics == c.harmonics && d.form == c.form &&
          d.system == c.system && d.median_seconds > 0)
        c.ratio_to_dogleg = c.median_seconds / d.median_seconds;

  nlohmann::json json = nlohmann::json::array();
  std::ofstream csv(out + "/bench.csv");
  csv << "scene,solver,system,form,harmonics,converged,termination,iterations,residual_evaluations,"
         "jacobian_evaluations,residual_norm,median_seconds,ratio_to_dogleg,relative_error_max_abs\n";
  for (const Case& c : cases) {
    json.push_back({{"scene", c.scene}, {"solver", c.solver}, {"system", c.system}, {"form", c.form},
                    {"harmonics", c.harmonics}, {"converged", c.converged}, {"termination", c.termination},
                    {"iterations", c.iterations}, {"residual_evaluations", c.residual_evaluations},
                    {"jacobian_evaluations", c.jacobian_evaluations}, {"residual_norm", c.residual_norm},
                    {"median_seconds", c.median_seconds}, {"ratio_to_dogleg", c.ratio_to_dogleg},
                    {"relative_error_max_abs", std::isnan(c.error_max_abs) ? nlohmann::json() : nlohmann::json(c.error_max_abs)}});
    csv << c.scene << "," << c.solver << "," << c.system << "," << c.form << "," << c.harmonics << ","
        << (c.converged ? "true" : "false") << "," << c.termination << "," << c.iterations << ","
        << c.residual_evaluations << "," << c.jacobian_evaluations << "," << c.residual_norm << ","
        << c.median_seconds << "," << c.ratio_to_dogleg << "," << c.error_max_abs << "\n";
  }
  std::ofstream(out + "/bench.json") << json.dump(2) << "\n";

  std::ostringstream table;
  table << "| scene | H | form | system | solver | converged | iterations | f-evals | J-evals | ‖g‖ | median s | / dogleg | rel. err max\\|x\\| |\n"
        << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Case& c : cases)
    table << "| " << c.scene << " | " << c.harmonics << " | " << c.form << " | " << c.system << " | "
          << c.solver << " | " << (c.converged ? "yes" : "**no** (" + c.termination + ")") << " | "
          << c.iterations << " | " << c.residual_evaluations << " | " << c.jacobian_evaluations << " | "
          << c.residual_norm << " | " << c.median_seconds << " | " << c.ratio_to_dogleg << " | "
          << c.error_max_abs << " |\n";
  std::cout << table.str();

  auto own = makeSolver("dogleg");
  std::string mgh_table = "(MINPACK backend not built)\n";
  for (const auto& entry : registeredSolvers())
    if (entry.name == "minpack") {
      auto reference = makeSolver("minpack");
      mgh_table = mgh::markdownTable(mgh::compare(*own, *reference, mgh::standardCases()));
    }
  std::ofstream report(out + "/report.md");
  report << "# eqhb benchmark report\n\n"
         << "Every case starts from a zero initial guess; tolerance ‖g‖₂ <= 1e-10; times are medians of "
         << repeats << " solves on this machine. Accuracy: relative error of max|x| on the law's DOF "
         << "against the same scene solved with 8x the default harmonics (exact min/max form).\n\n"
         << "## Solves\n\n" << table.str()
         << "\nWork-precision charts: work_precision_SCENE.png / .svg beside this report.\n"
         << "\n## Own dogleg vs MINPACK hybrj on the Moré–Garbow–Hillstrom problems\n\n" << mgh_table;
  std::cerr << "wrote " << out << "/bench.json, bench.csv, report.md\n";
  return 0;
}
