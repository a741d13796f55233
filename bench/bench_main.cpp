// eqhb-bench, the main job: on every scene, every backend and formulation
// (law form, full vs condensed) at the scene's harmonics, each solve
// repeated for a median time, with its accuracy against the time-domain
// reference and against a 4x-H solution; the backend comparison on
// friction-1d at H = 10 and 40; and the MGH comparison of the own dogleg
// with MINPACK. Writes bench.json, bench.csv, report.md into --out.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "eqhb/continuation/continuation.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/references/time_integrator.h"
#include "compliant_study.h"
#include "failure_maps.h"
#include "run_metadata.h"
#include "mgh/mgh_problems.h"
#include "scale_study.h"
#include "eqhb/backends/registry.h"
#include "terminal/progress.h"
#include "terminal/verbosity.h"
#include "report_number.h"

namespace fs = std::filesystem;
using namespace eqhb;

namespace {

struct Case {
  std::string study, scene, solver, system, form;
  int harmonics = 0;
  bool converged = false;
  std::string termination;
  int iterations = 0, residual_evaluations = 0, jacobian_evaluations = 0, repeats = 0;
  double residual_norm = NAN, median_seconds = NAN, ratio_to_dogleg = NAN;
  double error_reference = NAN;  // relative L2 of x (worst DOF) vs the time-domain reference
  double error_high_h = NAN;     // the same vs the 4x-H solution
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double worstDisplacementError(const std::vector<ChannelError>& errors) {
  double worst = 0.0;
  for (const auto& e : errors)
    if (e.label[0] == 'x') worst = std::max(worst, e.relative_l2);
  return worst;
}

// Period-to-period change below which a time run serves as reference.
constexpr double kUsableChange = 1e-4;

// What each scene is checked against.
struct Truth {
  std::string scene;
  TimeReference reference;
  bool has_reference = false;
  HbModel high_model;
  Eigen::VectorXd high;  // converged 4x-H solution, empty if none
};

Truth buildTruth(const fs::path& path, double step, int max_periods) {
  Truth truth;
  const Scene base = loadScene(path.string());
  truth.scene = base.name;
  // Highest-H solution by continuation from the scene's own H.
  CondensedSystem low(base.model);
  auto solver = makeSolver("dogleg");
  SolverResult r = solver->solve(low, Eigen::VectorXd::Zero(low.size()), {});
  if (!r.converged()) {
    FullSystem full(base.model);
    r = solver->solve(full, Eigen::VectorXd::Zero(full.size()), {});
    if (r.converged()) r.solution = low.fromFullCoefficients(full.fullCoefficients(r.solution));
  }
  const int h4 = 4 * base.model.basis.count();
  const Scene high = loadScene(path.string(), {"harmonic_balance.harmonics=" + std::to_string(h4),
                                               "harmonic_balance.samples=" +
                                                   std::to_string(std::max(base.model.samples, 16 * h4))});
  truth.high_model = high.model;
  if (r.converged()) {
    FullSystem high_system(high.model);
    const Eigen::VectorXd start = transferCoefficients(base.model, high.model, low.fullCoefficients(r.solution));
    const SolverResult rh = solver->solve(high_system, start, {});
    if (rh.converged()) truth.high = rh.solution;
    std::cerr << base.name << ": " << h4 << "-harmonic solution " << terminationName(rh.termination) << "\n";
  }
  TimeOptions options;
  options.step = step;
  options.max_periods = max_periods;
  options.periodic_tolerance = 1e-7;
  truth.reference = integrateToSteadyState(base.model, options,
                                           truth.high.size() ? transferCoefficients(high.model, base.model, truth.high)
                                                             : Eigen::VectorXd());
  // A slowly settling run is still a usable reference once its period-to-
  // period change is far below the harmonic-balance errors it judges.
  truth.has_reference = truth.reference.periodicity_error <= kUsableChange;
  std::cerr << base.name << ": time reference " << (truth.reference.periodic ? "periodic" : "NOT periodic")
            << " after " << truth.reference.periods << " periods (change " << truth.reference.periodicity_error
            << "), " << truth.reference.seconds << " s\n";
  return truth;
}

Case runCase(const std::string& study, const fs::path& path, const std::vector<std::string>& set,
             const std::string& solver_name, bool condensed, int repeats, double time_limit, const Truth* truth) {
  const Scene scene = loadScene(path.string(), set);
  Case c;
  c.study = study;
  c.scene = scene.name;
  c.solver = solver_name;
  c.system = condensed ? "condensed" : "full";
  c.harmonics = scene.model.basis.count();
  std::unique_ptr<HbSystem> system;
  try {
    system = makeHbSystem(scene.model, condensed);
  } catch (const std::exception& e) {
    c.termination = "not_applicable";
    return c;
  }
  auto solver = makeSolver(solver_name);
  SolverOptions options;
  options.time_limit = time_limit;
  std::vector<double> times;
  SolverResult r;
  double spent = 0.0;  // repeat for a stable median; slow cases are repeated less
  for (int i = 0; i < repeats && (i == 0 || spent < 1.0); ++i) {
    r = solver->solve(*system, Eigen::VectorXd::Zero(system->size()), options);
    times.push_back(r.seconds);
    spent += r.seconds;
  }
  c.repeats = static_cast<int>(times.size());
  c.converged = r.converged();
  c.termination = terminationName(r.termination);
  c.iterations = r.iterations;
  c.residual_evaluations = r.residual_evaluations;
  c.jacobian_evaluations = r.jacobian_evaluations;
  c.residual_norm = r.final_norm;
  c.median_seconds = r.termination == Termination::kInvalidOptions ? NAN : median(times);
  if (c.converged && truth) {
    const Eigen::VectorXd full = system->fullCoefficients(r.solution);
    if (truth->has_reference) c.error_reference = worstDisplacementError(compareWithReference(scene.model, full, truth->reference));
    if (truth->high.size()) {
      // Compare on the 4x-H basis: this solution padded with zeros.
      const Eigen::VectorXd padded = transferCoefficients(scene.model, truth->high_model, full);
      const int n = scene.model.structure.dofs(), nb = truth->high_model.basis.size();
      // Per DOF, relative to the DOF's own size floored like the time
      // reference's channels (a DOF at rest is not divided by its noise).
      double largest = 0.0, worst = 0.0;
      for (int i = 0; i < n; ++i) largest = std::max(largest, truth->high.segment(i * nb, nb).norm());
      for (int i = 0; i < n; ++i)
        worst = std::max(worst, (padded.segment(i * nb, nb) - truth->high.segment(i * nb, nb)).norm() /
                                    std::max({truth->high.segment(i * nb, nb).norm(), kChannelFloor * largest, 1e-300}));
      c.error_high_h = worst;
    }
  }
  return c;
}

std::string number(double x) { return bench::reportNumber(x, 3, "-"); }

std::string table(const std::vector<Case>& cases, const std::string& study) {
  std::ostringstream t;
  t << "| scene | H | form | system | solver | converged | iterations | f-evals | J-evals | ‖g‖ | median s | / dogleg | L2 err vs time ref | L2 err vs 4H |\n"
    << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Case& c : cases) {
    if (c.study != study) continue;
    t << "| " << c.scene << " | " << c.harmonics << " | " << c.form << " | " << c.system << " | " << c.solver << " | "
      << (c.converged ? "yes" : "**no** (" + c.termination + ")") << " | " << c.iterations << " | "
      << c.residual_evaluations << " | " << c.jacobian_evaluations << " | " << number(c.residual_norm) << " | "
      << number(c.median_seconds) << " | " << number(c.ratio_to_dogleg) << " | " << number(c.error_reference)
      << " | " << number(c.error_high_h) << " |\n";
  }
  return t.str();
}

// Its arguments printed one after the other.
template <class... Args>
std::string cat(const Args&... args) {
  std::ostringstream text;
  (text << ... << args);
  return text.str();
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"eqhb-bench: solvers x formulations on every scene"};
  std::string problems = EQHB_PROBLEMS_DIR, out = "results";
  bool quick = false;
  int repeats = 7;
  double reference_step = 2e-4;
  app.add_option("--problems", problems, "Folder of scene files");
  app.add_option("--out", out, "Output folder");
  app.add_flag("--quick", quick, "Short run: fewer backends, forms and repeats");
  bool scale_only = false;
  app.add_flag("--scale-only", scale_only, "Run the scale study alone (scale.csv, scale.md)");
  bool compliant_only = false;
  app.add_flag("--compliant-only", compliant_only,
               "Run the compliant-vs-Signorini study alone (compliant.csv, compliant.md)");
  app.add_option("--repeats", repeats, "Solves per case for the median time (capped at ~1 s per case)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--reference-step", reference_step, "Time step of the time-domain references");
  eqhb::cli::addVerbosityOptions(app);
  CLI11_PARSE(app, argc, argv);
  // Progress per study on stderr (elapsed, ETA); each case's line with --verbose.
  using eqhb::cli::ProgressLine;
  const auto& verbosity = eqhb::cli::verbosity();
  auto note = [&](ProgressLine& line, const std::string& text) {
    if (verbosity.verbose) line.message(text);
  };
  auto count = [](const char* what, size_t done, size_t total) {
    return std::string(what) + " " + std::to_string(done) + "/" + std::to_string(total);
  };
  if (quick) repeats = std::min(repeats, 3);
  fs::create_directories(out);
  // Compliant normal contact against the exact Signorini law, k_n = 1 .. 1e6
  // (compliant.csv; returns the report's table).
  auto compliantStudy = [&]() -> std::string {
    const fs::path scene = fs::path(problems) / "contact-friction-2d.toml";
    if (!fs::exists(scene)) return "(contact-friction-2d not in --problems)\n";
    const std::vector<double> stiffnesses =
        quick ? std::vector<double>{1.0, 1e2, 1e4, 1e6} : std::vector<double>{1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6};
    const auto rows = bench::compliantStudy(scene, stiffnesses);
    std::ofstream f(out + "/compliant.csv");
    f << "scene,system,k_n,converged,termination,iterations,residual_evaluations,seconds,distance,penetration\n";
    for (const auto& r : rows)
      f << r.scene << "," << r.system << "," << r.k_n << "," << (r.converged ? "true" : "false") << ","
        << r.termination << "," << r.iterations << "," << r.residual_evaluations << "," << r.seconds << ","
        << r.distance << "," << r.penetration << "\n";
    return bench::compliantReport(rows);
  };
  if (compliant_only) {
    std::ofstream(out + "/compliant.md") << "# eqhb: compliant vs exact Signorini contact\n\n"
                                         << bench::compliantIntroduction() << compliantStudy();
    std::cout << "compliant study: " << out << "/compliant.md, " << out << "/compliant.csv\n";
    return 0;
  }
  if (scale_only) {
    const std::vector<bench::ScaleRow> scale = bench::runScaleStudy(quick, scaleBackends(quick), problems);
    bench::writeScaleCsv(out + "/scale.csv", scale);
    std::ofstream(out + "/scale.md") << "# eqhb scale study\n\n" << scaleIntroduction() << bench::scaleReport(scale);
    std::cout << "scale study: " << out << "/scale.md, " << out << "/scale.csv\n";
    return 0;
  }

  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(problems))
    if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  // Structures with many DOFs (beams, finite-element models) are measured in
  // the scale study; the per-scene tables compare formulations and backends
  // on the small scenes, where a time-domain reference is affordable.
  std::vector<fs::path> structure_scenes;
  scenes.erase(std::remove_if(scenes.begin(), scenes.end(),
                              [&](const fs::path& path) {
                                const bool large = loadScene(path.string()).model.structure.dofs() > 20;
                                if (large) structure_scenes.push_back(path);
                                return large;
                              }),
               scenes.end());
  std::vector<std::string> all_backends;
  for (const auto& e : registeredSolvers()) all_backends.push_back(e.name);
  const std::vector<std::string> scene_backends =
      quick ? std::vector<std::string>{"dogleg", "dogleg-newton", "minpack"}
            : std::vector<std::string>{"dogleg", "dogleg-newton", "minpack", "ceres-lm", "ceres-dogleg",
                                       "ipopt-ls", "ipopt-square", "nlopt-slsqp"};

  std::vector<Case> cases;
  struct TruthStatus {
    std::string scene;
    bool periodic;
    int periods;
    double change, seconds;
    bool used, high;
  };
  std::vector<TruthStatus> truths;
  // 1. Backends on friction-1d (exact min/max form), H = 10 and 40.
  const fs::path friction = fs::path(problems) / "friction-1d.toml";
  if (fs::exists(friction)) {
    const std::vector<int> hs = quick ? std::vector<int>{10} : std::vector<int>{10, 40};
    ProgressLine line(verbosity.progress, "bench 1/5 backends");
    const size_t total = hs.size() * 2 * all_backends.size();
    for (int h : hs)
      for (bool condensed : {true, false})
        for (const auto& name : all_backends) {
          Case c = runCase("backends", friction, {"harmonic_balance.harmonics=" + std::to_string(h)}, name, condensed,
                           repeats, 5.0, nullptr);
          c.form = "minmax";
          cases.push_back(c);
          note(line, cat("  backends H=", h, " ", c.system, " ", name, ": ", c.termination));
          line.update(static_cast<double>(cases.size()) / total, count("case", cases.size(), total));
        }
    line.finish();
  }

  // 2. Every scene x form x system x backend at the scene's harmonics.
  ProgressLine scenes_line(verbosity.progress, "bench 2/5 scenes");
  for (const auto& path : scenes) {
    const size_t scene_index = &path - scenes.data();
    scenes_line.update(static_cast<double>(scene_index) / scenes.size(), count("scene", scene_index + 1, scenes.size()),
                       path.stem().string());
    const Scene base = loadScene(path.string());
    const Truth truth = buildTruth(path, reference_step, quick ? 40 : 200);
    truths.push_back({truth.scene, truth.reference.periodic, truth.reference.periods,
                      truth.reference.periodicity_error, truth.reference.seconds, truth.has_reference,
                      truth.high.size() > 0});
    std::vector<std::string> forms = {""};
    if (!base.model.laws.empty() && !lawForms(base.model.laws[0].law->type()).empty())
      forms = lawForms(base.model.laws[0].law->type());
    if (quick) forms.resize(1);
    // (label, overrides) per formulation: each form of the first law's type;
    // for contact-friction also each normal form with the max friction form
    // (the scenes' own is projection).
    std::vector<std::pair<std::string, std::vector<std::string>>> formulations;
    for (const auto& form : forms)
      formulations.push_back({form.empty() ? "-" : form,
                              form.empty() ? std::vector<std::string>{} : lawOverrides(base.model, "form", form)});
    if (!quick && !base.model.laws.empty() && base.model.laws[0].law->type() == "contact-friction")
      for (const auto& form : forms) {
        std::vector<std::string> set = lawOverrides(base.model, "form", form);
        for (size_t l = 0; l < base.model.laws.size(); ++l)
          if (base.model.laws[l].law->type() == "contact-friction")
            set.push_back("law[" + std::to_string(l) + "].friction_form=\"max\"");
        formulations.push_back({form + ", friction max", set});
      }
    for (const auto& [form, set] : formulations)
      for (bool condensed : {true, false})
        for (const auto& name : scene_backends) {
          if (std::find(all_backends.begin(), all_backends.end(), name) == all_backends.end()) continue;
          Case c = runCase("scenes", path, set, name, condensed, repeats, 2.0, &truth);
          c.form = form;
          note(scenes_line, cat("  ", c.scene, " ", c.form, " ", c.system, " ", name, ": ", c.termination, " ",
                                c.median_seconds, " s"));
          scenes_line.update(static_cast<double>(scene_index) / scenes.size(),
                             count("scene", scene_index + 1, scenes.size()), c.scene + " " + c.form + " " + name);
          cases.push_back(c);
        }
    // Variants of the default formulation: ρ an order of magnitude off its
    // default, and twice the harmonics.
    if (quick) continue;
    const std::string default_form = forms[0].empty() ? "-" : forms[0];
    std::vector<std::pair<std::string, std::vector<std::string>>> variants;
    for (const char* rho : {"0.1", "10"}) {
      const auto set = lawOverrides(base.model, "rho", rho);
      if (!set.empty()) variants.push_back({default_form + ", rho=" + rho, set});
    }
    const int h2 = 2 * base.model.basis.count();
    variants.push_back({default_form, {"harmonic_balance.harmonics=" + std::to_string(h2),
                                       "harmonic_balance.samples=" + std::to_string(std::max(base.model.samples, 16 * h2))}});
    for (const auto& [label, set] : variants)
      for (bool condensed : {true, false})
        for (const std::string name : {"dogleg", "dogleg-newton", "minpack", "ipopt-ls"}) {
          if (std::find(all_backends.begin(), all_backends.end(), name) == all_backends.end()) continue;
          Case c = runCase("variants", path, set, name, condensed, repeats, 2.0, &truth);
          c.form = label;
          note(scenes_line,
               cat("  ", c.scene, " H=", c.harmonics, " ", c.form, " ", c.system, " ", name, ": ", c.termination));
          scenes_line.update(static_cast<double>(scene_index) / scenes.size(),
                             count("scene", scene_index + 1, scenes.size()), c.scene + " " + c.form + " " + name);
          cases.push_back(c);
        }
  }
  scenes_line.finish(std::to_string(cases.size()) + " cases");

  for (Case& c : cases)
    for (const Case& d : cases)
      if (d.solver == "dogleg" && d.study == c.study && d.scene == c.scene && d.harmonics == c.harmonics &&
          d.form == c.form && d.system == c.system && d.median_seconds > 0)
        c.ratio_to_dogleg = c.median_seconds / d.median_seconds;

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
  const nlohmann::json metadata = bench::runMetadata();
  std::ofstream(out + "/bench.json") << nlohmann::json{{"metadata", metadata}, {"cases", json}}.dump(2) << "\n";

  // 3. Failure maps.
  std::vector<bench::FailureRow> failures;
  const std::vector<std::string> map_backends =
      quick ? std::vector<std::string>{"dogleg", "dogleg-newton", "ceres-dogleg"}
            : std::vector<std::string>{"dogleg", "dogleg-newton", "minpack", "ceres-lm", "ceres-dogleg", "ipopt-ls",
                                       "nlopt-slsqp"};
  ProgressLine maps_line(verbosity.progress, "bench 3/5 failure maps");
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
      if (std::find(all_backends.begin(), all_backends.end(), b) != all_backends.end()) available.push_back(b);
    const auto rows = bench::failureMaps(path, available, quick);
    failures.insert(failures.end(), rows.begin(), rows.end());
  }
  maps_line.finish(std::to_string(failures.size()) + " solves");
  {
    std::ofstream f(out + "/failure_maps.csv");
    f << "scene,grid,solver,value,seed,converged,termination,iterations,seconds\n";
    for (const auto& r : failures)
      f << r.scene << "," << r.grid << "," << r.solver << "," << r.value << "," << r.seed << ","
        << (r.converged ? "true" : "false") << "," << r.termination << "," << r.iterations << "," << r.seconds << "\n";
  }
  std::ostringstream success;
  {
    std::map<std::string, std::pair<int, int>> rate;  // solver -> (converged, total)
    for (const auto& r : failures) {
      auto& [ok, total] = rate[r.solver];
      ok += r.converged;
      ++total;
    }
    success << "| backend | converged | cases | success rate |\n|---|---|---|---|\n";
    for (const auto& [solver, counts] : rate)
      success << "| " << solver << " | " << counts.first << " | " << counts.second << " | "
              << number(100.0 * counts.first / std::max(1, counts.second)) << " % |\n";
  }

  const std::string compliant_table = compliantStudy();

  // 4. Frequency-response curves of every scene with a [sweep].
  std::ostringstream curves;
  ProgressLine curves_line(verbosity.progress, "bench 4/5 curves");
  for (const auto& path : scenes) {
    const Scene scene = loadScene(path.string());
    const size_t scene_index = &path - scenes.data();
    curves_line.update(static_cast<double>(scene_index) / scenes.size(), count("scene", scene_index + 1, scenes.size()),
                       scene.name);
    if (!scene.sweep_from) continue;
    auto solver = makeSolver("dogleg");
    ContinuationOptions options;
    options.from = *scene.sweep_from;
    options.to = *scene.sweep_to;
    options.step = std::abs(options.to - options.from) / (quick ? 50 : 200);  // a sweep may run downwards
    options.max_points = quick ? 1500 : 6000;
    options.condensed = path.stem() != "contact";  // contact: only the full system starts cold
    const Curve sequential = sweepSequential(scene.model, *solver, {}, options);
    options.step = 0.01;
    options.max_step = 1.0;
    const Curve arclength = sweepArclength(scene.model, *solver, {}, options);
    const int dofs = scene.model.structure.dofs();
    writeCurveCsv(out + "/curve_" + scene.name + "_sequential.csv", sequential, dofs);
    writeCurveCsv(out + "/curve_" + scene.name + "_arclength.csv", arclength, dofs);
    curves << "| " << scene.name << " | " << sequential.points.size() << " | " << sequential.failed_points << " | "
           << number(sequential.seconds) << " | " << arclength.points.size() << " | " << arclength.fold_omegas.size()
           << " | " << arclength.stop_reason << " | " << number(arclength.seconds) << " |\n";
    note(curves_line, cat("  curves ", scene.name, ": sequential ", sequential.failed_points, " failed, arclength ",
                          arclength.stop_reason));
  }
  curves_line.finish();

  std::string mgh_table = "(MINPACK backend not built)\n";
  if (std::find(all_backends.begin(), all_backends.end(), "minpack") != all_backends.end()) {
    auto own = makeSolver("dogleg");
    auto reference = makeSolver("minpack");
    mgh_table = mgh::markdownTable(mgh::compare(*own, *reference, mgh::standardCases()));
  }
  std::ostringstream truth_table;
  truth_table << "| scene | time reference | periods | period-to-period change | seconds | used | 4x-H solution |\n"
              << "|---|---|---|---|---|---|---|\n";
  for (const auto& t : truths)
    truth_table << "| " << t.scene << " | " << (t.periodic ? "periodic" : "not periodic") << " | " << t.periods << " | "
                << number(t.change) << " | " << number(t.seconds) << " | " << (t.used ? "yes" : "no") << " | "
                << (t.high ? "converged" : "not available") << " |\n";

  // Which backend to pick, per scene, from the data: most formulations
  // converged, then the lowest median time over the converged cases.
  const char* const advice_rule =
      "per scene, the backend that converged in the most formulations (every form of the scene's laws, "
      "condensed and full system, zero start); ties go to the lowest median time over its converged cases";
  std::ostringstream advice, in_short;
  {
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
  }

  // 5. Scale study (its own CSV: the quick run's smallest sizes are not in
  // the perf-check baseline).
  ProgressLine scale_line(verbosity.progress, "bench 5/5 scale study");
  scale_line.update(-1.0, "running");
  const std::vector<bench::ScaleRow> scale = bench::runScaleStudy(
      quick, scaleBackends(quick), problems);
  scale_line.finish(std::to_string(scale.size()) + " cases");
  bench::writeScaleCsv(out + "/scale.csv", scale);
  std::string structure_names;
  for (const auto& path : structure_scenes) structure_names += (structure_names.empty() ? "" : ", ") + path.stem().string();

  std::ofstream report(out + "/report.md");
  std::string libraries;
  for (const auto& [name, version] : metadata["libraries"].items())
    libraries += (libraries.empty() ? "" : ", ") + name + " " + version.get<std::string>();
  report << "# eqhb benchmark report\n\n"
         << "## Summary\n\n"
         << "What to pick for each scene (rule: " << advice_rule << "):\n\n"
         << "| scene | backend | formulations converged | median s |\n|---|---|---|---|\n" << in_short.str()
         << "\nRun: eqhb " << metadata["eqhb_version"].get<std::string>() << ", commit "
         << metadata["commit"].get<std::string>() << (metadata["uncommitted_changes"].get<bool>() ? " (+ changes)" : "")
         << ", " << metadata["date"].get<std::string>() << ", " << metadata["cpu"].get<std::string>() << " ("
         << metadata["hardware_threads"].get<unsigned>() << " threads), " << metadata["compiler"].get<std::string>()
         << " " << metadata["build_type"].get<std::string>() << "; " << libraries << ".\n\n"
         << "Every solve starts from a zero initial guess with tolerance ‖g‖₂ <= 1e-10; times are medians of up to "
         << repeats << " solves (fewer for slow cases) on this machine. Accuracy: relative L2 error over one "
         << "period of the displacements (worst DOF) against the time-domain reference (Moreau–Jean, h = "
         << reference_step << ") and against the same scene solved with 4x the harmonics.\n\n"
         << "## Backends on friction-1d\n\n" << table(cases, "backends")
         << "\n## Which backend for which scene\n\nThe rule: " << advice_rule << ".\n\n" << advice.str()
         << "\n## References of truth\n\n" << truth_table.str()
         << "\nA time run whose period-to-period change is at most " << kUsableChange
         << " is used as reference even if it has not met the 1e-7 periodicity tolerance.\n"
         << "\n## Scenes, formulations and backends\n\n" << table(cases, "scenes")
         << "\n![performance profile](performance_profile.png)\n"
         << "\n## Variants: rho and harmonics\n\nThe scene's first form with rho = 0.1 and 10, and with twice the "
         << "harmonics, on both systems.\n\n" << table(cases, "variants")
         << "\n## Failure maps\n\nSuccess over the grids of initial guesses, harmonics, rho and forcing "
         << "(failure_maps.csv, charts failure_map_SCENE.png):\n\n" << success.str()
         << "\n## Compliant vs exact Signorini contact\n\n" << bench::compliantIntroduction() << compliant_table
         << "\n## Frequency-response curves\n\n| scene | sequential points | failed | s | arclength points | folds | arclength stop | s |\n"
         << "|---|---|---|---|---|---|---|---|\n" << curves.str()
         << "\nCharts: curve_SCENE_*.png/.svg, work_precision_SCENE.png/.svg, convergence_*.png/.svg, "
         << "micro-benchmark slopes in micro.md.\n"
         << "\n## Own dogleg vs MINPACK hybrj on the Moré–Garbow–Hillstrom problems\n\n" << mgh_table
         << "\n## Scale study\n\n" << scaleIntroduction() << "Structure "
         << "scenes measured here rather than in the scene tables: " << (structure_names.empty() ? "none" : structure_names)
         << ". Data: scale.csv; chart: scale.png/.svg.\n" << bench::scaleReport(scale)
         << "\n![scale study](scale.png)\n";
  std::cout << table(cases, "backends") << "\n" << table(cases, "scenes");
  std::cerr << "wrote " << out << "/bench.json, bench.csv, report.md\n";
  return 0;
}
