#include "solve_command.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "eqhb/error.h"
#include "eqhb/hb_solution.h"
#include "eqhb/hb_systems.h"
#include "eqhb/invariants.h"
#include "eqhb/scene.h"
#include "registry.h"

namespace eqhb::cli {

void addSolveCommand(CLI::App& app, SolveArguments& a) {
  auto* cmd = app.add_subcommand("solve", "Solve one scene at one frequency");
  cmd->add_option("scene", a.scene, "Scene file (problems/*.toml)")->required();
  cmd->add_option("--omega", a.omega, "Forcing frequency ω (overrides harmonic_balance.omega)");
  cmd->add_option("--harmonics", a.harmonics, "Highest harmonic H");
  cmd->add_option("--samples", a.samples, "Time samples N per period (>= 2H+1)");
  cmd->add_option("--solver", a.solver, "Backend name (see `eqhb solvers`)");
  cmd->add_option("--form", a.form, "Law form for every friction law: minmax|projection|tanh|piecewise");
  cmd->add_option("--rho", a.rho, "Scaling ρ > 0 of every exact law");
  auto* condensed = cmd->add_flag("--condensed", "Solve the condensed system (unknowns: law forces; default)");
  cmd->add_flag("--full", a.full, "Solve the full system (displacements and forces)")->excludes(condensed);
  cmd->add_flag("--json", a.json, "Print one JSON object");
  cmd->add_flag("--trajectory", a.trajectory, "With --json: add the samples of x and of the law forces over one period");
  cmd->add_option("--set", a.overrides, "Override a scene value: PATH=VALUE, e.g. law[0].muN=5");
  cmd->add_option("--option", a.backend_options, "Backend-specific option NAME=VALUE");
  cmd->add_option("--tolerance", a.tolerance, "Residual tolerance on ‖g‖₂")->capture_default_str();
  cmd->add_option("--max-iterations", a.max_iterations, "Iteration limit")->capture_default_str();
  cmd->add_option("--max-evaluations", a.max_evaluations, "Residual evaluation limit")->capture_default_str();
  cmd->add_option("--time-limit", a.time_limit, "Seconds per solve, 0 = none")->capture_default_str();
  cmd->add_option("--repeat", a.repeat, "Repeat the solve and report the median time")
      ->check(CLI::Range(1, 100000));
}

namespace {

std::vector<std::string> sceneOverrides(const SolveArguments& a) {
  std::vector<std::string> o = a.overrides;
  auto num = [](double x) { return formatNumber(x); };
  if (a.omega) o.push_back("harmonic_balance.omega=" + num(*a.omega));
  if (a.harmonics) o.push_back("harmonic_balance.harmonics=" + std::to_string(*a.harmonics));
  if (a.samples) o.push_back("harmonic_balance.samples=" + std::to_string(*a.samples));
  if (a.form || a.rho) {
    // --form and --rho apply to every law that has them: look at the scene first.
    const Scene plain = loadScene(a.scene, a.overrides);
    int touched = 0;
    for (size_t l = 0; l < plain.model.laws.size(); ++l) {
      const std::string type = plain.model.laws[l].law->type();
      const auto& forms = lawForms(type);
      const bool takes_form = a.form && std::find(forms.begin(), forms.end(), *a.form) != forms.end();
      const bool takes_rho = a.rho && type != "cubic";
      const std::string law = "law[" + std::to_string(l) + "].";
      if (takes_form) o.push_back(law + "form=\"" + *a.form + "\"");
      if (takes_rho) o.push_back(law + "rho=" + num(*a.rho));
      touched += takes_form || takes_rho;
    }
    if (touched == 0)
      throwInputError(a.form ? "--form" : "--rho", a.form ? *a.form : num(*a.rho),
                      "no law of the scene takes it");
  }
  return o;
}

nlohmann::json coefficientsJson(const HarmonicSet& basis, const Eigen::VectorXd& c) {
  nlohmann::json harmonics = nlohmann::json::array(), cos = nlohmann::json::array(),
                 sin = nlohmann::json::array();
  for (size_t h = 0; h < basis.harmonics().size(); ++h) {
    const int k = basis.harmonics()[h], o = basis.offset(static_cast<int>(h));
    harmonics.push_back(k);
    cos.push_back(c[o]);
    sin.push_back(k == 0 ? 0.0 : c[o + 1]);
  }
  return {{"harmonics", harmonics}, {"cos", cos}, {"sin", sin}};
}

}  // namespace

int runSolve(const SolveArguments& a) {
  const Scene scene = loadScene(a.scene, sceneOverrides(a));
  const HbModel& model = scene.model;
  std::unique_ptr<HbSystem> system;
  if (a.full) system = std::make_unique<FullSystem>(model);
  else system = std::make_unique<CondensedSystem>(model);

  SolverOptions options;
  options.residual_tolerance = a.tolerance;
  options.max_iterations = a.max_iterations;
  options.max_evaluations = a.max_evaluations;
  options.time_limit = a.time_limit;
  for (const auto& kv : a.backend_options) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) throwInputError("--option", kv, "must be NAME=VALUE");
    options.backend[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  std::string why;
  if (!options.isValid(&why)) throw InputError(why);
  auto solver = makeSolver(a.solver);

  const Eigen::VectorXd z0 = Eigen::VectorXd::Zero(system->size());
  SolverResult result;
  std::vector<double> times;
  for (int i = 0; i < a.repeat; ++i) {
    result = solver->solve(*system, z0, options);
    if (result.termination == Termination::kInvalidOptions)
      throw InputError("--option: " + result.native_message);
    times.push_back(result.seconds);
  }
  std::sort(times.begin(), times.end());
  const double median = times.size() % 2 ? times[times.size() / 2]
                                         : 0.5 * (times[times.size() / 2 - 1] + times[times.size() / 2]);
  const HbSolution solution = summarize(model, system->fullCoefficients(result.solution));

  if (a.json) {
    nlohmann::json out;
    out["scene"] = scene.name;
    out["solver"] = result.solver;
    out["system"] = system->condensed() ? "condensed" : "full";
    out["unknowns"] = system->size();
    out["omega"] = model.omega;
    out["harmonics"] = model.basis.count();
    out["highest_harmonic"] = model.basis.highest();
    out["harmonic_set"] = HarmonicSet::kindName(model.basis.kind());
    out["samples"] = model.samples;
    out["converged"] = result.converged();
    out["termination"] = terminationName(result.termination);
    out["native_code"] = result.native_code;
    out["native_message"] = result.native_message;
    out["iterations"] = result.iterations;
    out["residual_evaluations"] = result.residual_evaluations;
    out["jacobian_evaluations"] = result.jacobian_evaluations;
    out["initial_residual_norm"] = result.initial_norm;
    out["residual_norm"] = result.final_norm;
    out["tolerance"] = options.residual_tolerance;
    out["seconds"] = median;
    out["repeats"] = a.repeat;
    out["seconds_min"] = times.front();
    out["seconds_max"] = times.back();
    nlohmann::json dofs = nlohmann::json::array();
    for (size_t i = 0; i < solution.displacements.size(); ++i) {
      const auto& c = solution.displacements[i];
      dofs.push_back({{"dof", i + 1}, {"max_abs", c.max_abs}, {"max_abs_velocity", c.max_abs_rate},
                      {"coefficients", coefficientsJson(model.basis, c.coefficients)}});
    }
    out["dofs"] = dofs;
    nlohmann::json laws = nlohmann::json::array();
    size_t q = 0;
    for (size_t l = 0; l < model.laws.size(); ++l) {
      nlohmann::json components = nlohmann::json::array();
      for (int a2 = 0; a2 < model.laws[l].law->dimension(); ++a2, ++q) {
        const auto& c = solution.forces[q];
        components.push_back({{"dof", model.laws[l].dofs[a2] + 1}, {"max_abs", c.max_abs},
                              {"coefficients", coefficientsJson(model.basis, c.coefficients)}});
      }
      const double max_abs = std::max_element(components.begin(), components.end(),
                                              [](const auto& x, const auto& y) {
                                                return x["max_abs"].template get<double>() <
                                                       y["max_abs"].template get<double>();
                                              })->at("max_abs").get<double>();
      laws.push_back({{"law", l + 1}, {"type", model.laws[l].law->type()}, {"max_abs", max_abs},
                      {"components", components}});
    }
    out["laws"] = laws;
    nlohmann::json invariants = nlohmann::json::array();
    for (const auto& report : checkInvariants(model, system->fullCoefficients(result.solution))) {
      nlohmann::json measures;
      for (const auto& [name, value] : report.violations) measures[name] = value;
      invariants.push_back({{"law", report.law + 1}, {"type", report.type}, {"violations", measures}});
    }
    out["invariants"] = invariants;
    if (a.trajectory) {
      // One period on the model's N samples: t, x per DOF, λ per law component.
      nlohmann::json t = nlohmann::json::array();
      for (int i = 0; i < model.samples; ++i) t.push_back(2 * M_PI / model.omega * i / model.samples);
      nlohmann::json trajectory = {{"t", t}};
      for (const auto& c : solution.displacements)
        trajectory[c.label] = std::vector<double>(c.samples.data(), c.samples.data() + c.samples.size());
      for (const auto& c : solution.forces)
        trajectory[c.label] = std::vector<double>(c.samples.data(), c.samples.data() + c.samples.size());
      out["trajectory"] = trajectory;
    }
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << scene.name << " at omega = " << model.omega << ", H = " << model.basis.count()
              << " (" << HarmonicSet::kindName(model.basis.kind()) << "), N = " << model.samples
              << ", " << (system->condensed() ? "condensed" : "full") << " system of "
              << system->size() << " unknowns\n"
              << result.summary() << "\n";
    if (a.repeat > 1) std::cout << "median time over " << a.repeat << " solves: " << median << " s\n";
    for (const auto& c : solution.displacements)
      std::cout << "  max|" << c.label << "| = " << c.max_abs << "\n";
    for (const auto& c : solution.forces) std::cout << "  max|" << c.label << "| = " << c.max_abs << "\n";
    for (const auto& report : checkInvariants(model, system->fullCoefficients(result.solution))) {
      std::cout << "  law " << report.law + 1 << " (" << report.type << ") worst violations:";
      for (const auto& [name, value] : report.violations) std::cout << " " << name << " " << value;
      std::cout << "\n";
    }
  }
  if (!result.converged())
    std::cerr << "eqhb: the solve did not converge: " << terminationName(result.termination)
              << ", |g| = " << result.final_norm << " > tolerance " << options.residual_tolerance
              << (result.native_message.empty() ? "" : " (" + result.native_message + ")") << "\n";
  return result.converged() ? 0 : 1;
}

}  // namespace eqhb::cli
