#include "time_commands.h"

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "eqhb/harmonic_balance/hb_solution.h"

namespace eqhb::cli {

namespace {

void addTimeOptions(CLI::App* cmd, TimeArguments& t) {
  cmd->add_option("--step", t.options.step, "Time step h (adjusted to divide the period)")->capture_default_str();
  cmd->add_option("--periods", t.options.max_periods, "Most periods to integrate")->capture_default_str();
  cmd->add_option("--theta", t.options.theta, "θ of the Moreau–Jean scheme, in [0.5, 1]")->capture_default_str();
  cmd->add_option("--periodic-tolerance", t.options.periodic_tolerance,
                  "Relative change of the period-start state that counts as periodic")
      ->capture_default_str();
  cmd->add_option("--restitution", t.options.restitution, "Newton impact coefficient of contact laws")
      ->capture_default_str();
}

nlohmann::json referenceJson(const HbModel& model, const TimeReference& ref) {
  nlohmann::json out = {{"periodic", ref.periodic},
                        {"periods", ref.periods},
                        {"step", ref.step},
                        {"steps_per_period", ref.steps_per_period},
                        {"periodicity_error", ref.periodicity_error},
                        {"seconds", ref.seconds}};
  const int nb = model.basis.size();
  nlohmann::json dofs = nlohmann::json::array();
  for (int i = 0; i < model.structure.dofs(); ++i)
    dofs.push_back({{"dof", i + 1},
                    {"max_abs", ref.displacement.col(i).cwiseAbs().maxCoeff()},
                    {"max_abs_velocity", ref.velocity.col(i).cwiseAbs().maxCoeff()},
                    {"first_harmonic_amplitude",
                     firstHarmonicAmplitude(model.basis, ref.coefficients.data() + i * nb)}});
  out["dofs"] = dofs;
  nlohmann::json forces = nlohmann::json::array();
  for (int q = 0; q < ref.force.cols(); ++q)
    forces.push_back({{"component", q + 1}, {"max_abs", ref.force.col(q).cwiseAbs().maxCoeff()}});
  out["law_forces"] = forces;
  return out;
}

// The last period, sample i at t = iT/steps_per_period: "t", then per DOF
// "x<i>" and "v<i>", per law component the label of `eqhb solve`.
nlohmann::json trajectoryJson(const HbModel& model, const TimeReference& ref) {
  const int samples = static_cast<int>(ref.displacement.rows());
  std::vector<double> t(samples);
  for (int i = 0; i < samples; ++i) t[i] = 2 * M_PI / model.omega * i / ref.steps_per_period;
  auto column = [](const Eigen::MatrixXd& m, int j) {
    const Eigen::VectorXd c = m.col(j);
    return std::vector<double>(c.data(), c.data() + c.size());
  };
  nlohmann::json out = {{"t", t}};
  for (int i = 0; i < model.structure.dofs(); ++i) {
    out["x" + std::to_string(i + 1)] = column(ref.displacement, i);
    out["v" + std::to_string(i + 1)] = column(ref.velocity, i);
  }
  const HbSolution labels = summarize(model, ref.coefficients);
  for (int q = 0; q < ref.force.cols(); ++q) out[labels.forces[q].label] = column(ref.force, q);
  return out;
}

void printReference(const HbModel& model, const TimeReference& ref) {
  std::cout << "time reference: " << (ref.periodic ? "periodic" : "NOT periodic") << " after " << ref.periods
            << " periods (change " << ref.periodicity_error << "), h = " << ref.step << " ("
            << ref.steps_per_period << " steps per period), " << ref.seconds << " s\n";
  for (int i = 0; i < model.structure.dofs(); ++i)
    std::cout << "  max|x" << i + 1 << "| = " << ref.displacement.col(i).cwiseAbs().maxCoeff() << "\n";
  for (int q = 0; q < ref.force.cols(); ++q)
    std::cout << "  max|lambda" << q + 1 << "| = " << ref.force.col(q).cwiseAbs().maxCoeff() << "\n";
}

}  // namespace

void addSimulateCommand(CLI::App& app, SolveArguments& s, TimeArguments& t) {
  auto* cmd = app.add_subcommand("simulate", "Integrate a scene in time to its periodic steady state (reference)");
  addSceneOptions(cmd, s.scene);
  addTimeOptions(cmd, t);
  cmd->add_flag("--from-hb", t.from_hb, "Start from the harmonic-balance solution instead of rest");
  cmd->add_option("--solver", s.solver, "Backend for --from-hb");
  cmd->add_flag("--json", s.json, "Print one JSON object");
  cmd->add_flag("--trajectory", s.trajectory,
                "With --json: add the last period's samples of x, dx/dt and the law forces");
}

void addCompareCommand(CLI::App& app, SolveArguments& s, TimeArguments& t) {
  auto* cmd = app.add_subcommand("compare", "Harmonic balance against the time-domain reference, with errors");
  addSceneOptions(cmd, s.scene);
  addSolverOptions(cmd, s);
  addTimeOptions(cmd, t);
  cmd->add_flag("--from-rest", t.from_rest, "Start the reference from rest (default: from the HB solution)");
  cmd->add_flag("--json", s.json, "Print one JSON object");
}

int runSimulate(const SolveArguments& s, const TimeArguments& t) {
  Eigen::VectorXd start;
  Scene scene = loadSceneWith(s.scene);
  if (t.from_hb) {
    const HbRun run = solveHarmonicBalance(s);
    if (!run.result.converged())
      throw std::runtime_error("--from-hb: the harmonic-balance solve did not converge (" +
                               std::string(terminationName(run.result.termination)) + ")");
    start = run.system->fullCoefficients(run.result.solution);
  }
  const TimeReference ref = integrateToSteadyState(scene.model, t.options, start);
  if (s.json) {
    nlohmann::json out = referenceJson(scene.model, ref);
    out["scene"] = scene.name;
    out["omega"] = scene.model.omega;
    if (s.trajectory) out["trajectory"] = trajectoryJson(scene.model, ref);
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << scene.name << " at omega = " << scene.model.omega << "\n";
    printReference(scene.model, ref);
  }
  if (!ref.periodic) std::cerr << "eqhb: no periodic steady state within " << ref.periods << " periods\n";
  return ref.periodic ? 0 : 1;
}

int runCompare(const SolveArguments& s, const TimeArguments& t) {
  const HbRun run = solveHarmonicBalance(s);
  const HbModel& model = run.scene.model;
  if (!run.result.converged())
    std::cerr << "eqhb: warning: the harmonic-balance solve did not converge ("
              << terminationName(run.result.termination) << "); errors refer to its last iterate\n";
  const Eigen::VectorXd hb = run.system->fullCoefficients(run.result.solution);
  const TimeReference ref = integrateToSteadyState(model, t.options, t.from_rest ? Eigen::VectorXd() : hb);
  const auto errors = compareWithReference(model, hb, ref);
  if (s.json) {
    nlohmann::json out;
    out["scene"] = run.scene.name;
    out["omega"] = model.omega;
    out["harmonics"] = model.basis.count();
    out["hb"] = {{"converged", run.result.converged()},
                 {"termination", terminationName(run.result.termination)},
                 {"residual_norm", run.result.final_norm},
                 {"seconds", run.result.seconds}};
    out["reference"] = referenceJson(model, ref);
    nlohmann::json e = nlohmann::json::array();
    for (const auto& c : errors)
      e.push_back({{"channel", c.label}, {"relative_l2", c.relative_l2}, {"relative_l2_velocity", c.relative_l2_rate},
                   {"relative_max_abs", c.relative_max_abs}, {"first_harmonic_error", c.first_harmonic_error},
                   {"max_abs_hb", c.max_abs_hb}, {"max_abs_reference", c.max_abs_reference}});
    out["errors"] = e;
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << run.scene.name << " at omega = " << model.omega << ", H = " << model.basis.count() << "\n"
              << "harmonic balance: " << run.result.summary() << "\n";
    printReference(model, ref);
    std::cout << "errors (HB vs reference):\n";
    for (const auto& c : errors)
      std::cout << "  " << c.label << ": L2 " << c.relative_l2 << (c.label[0] == 'x' ? ", velocity L2 " + std::to_string(c.relative_l2_rate) : "")
                << ", max|.| " << c.max_abs_hb << " vs " << c.max_abs_reference << " (" << c.relative_max_abs
                << "), first harmonic " << c.first_harmonic_error << "\n";
  }
  return run.result.converged() && ref.periodic ? 0 : 1;
}

}  // namespace eqhb::cli
