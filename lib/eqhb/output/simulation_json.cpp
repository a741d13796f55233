#include "eqhb/output/simulation_json.h"

#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_solution.h"

namespace eqhb::output {

nlohmann::json referenceJson(const HbModel& model, const TimeReference& ref) {
  nlohmann::json out = {{"periodic", ref.periodic},
                        {"timed_out", ref.timed_out},
                        {"periods", ref.periods},
                        {"step", ref.step},
                        {"steps_per_period", ref.steps_per_period},
                        {"periodicity_error", ref.periodicity_error},
                        {"seconds", ref.seconds}};
  const int nb = model.basis.size();
  nlohmann::json dofs = nlohmann::json::array();
  for (int i = 0; i < model.structure.dofs(); ++i)
    dofs.push_back({{"dof", i + 1},
                    {"name", dofLabel(model, i)},
                    {"max_abs", ref.displacement.col(i).cwiseAbs().maxCoeff()},
                    {"max_abs_velocity", ref.velocity.col(i).cwiseAbs().maxCoeff()},
                    {"first_harmonic_amplitude",
                     firstHarmonicAmplitude(model.basis, ref.coefficients.data() + i * nb)}});
  out["dofs"] = dofs;
  const std::vector<std::string> labels = lawComponentLabels(model);
  nlohmann::json forces = nlohmann::json::array();
  for (int q = 0; q < ref.force.cols(); ++q)
    forces.push_back({{"component", q + 1}, {"label", labels[q]}, {"max_abs", ref.force.col(q).cwiseAbs().maxCoeff()}});
  out["law_forces"] = forces;
  return out;
}

nlohmann::json referenceTrajectoryJson(const HbModel& model, const TimeReference& ref) {
  const int samples = static_cast<int>(ref.displacement.rows());
  std::vector<double> t(samples);
  for (int i = 0; i < samples; ++i) t[i] = 2 * M_PI / model.omega * i / ref.steps_per_period;
  auto column = [](const Eigen::MatrixXd& m, int j) {
    const Eigen::VectorXd c = m.col(j);
    return std::vector<double>(c.data(), c.data() + c.size());
  };
  nlohmann::json out = {{"t", t}};
  for (int i = 0; i < model.structure.dofs(); ++i) {
    out[dofLabel(i)] = column(ref.displacement, i);
    out["v" + std::to_string(i + 1)] = column(ref.velocity, i);
  }
  const std::vector<std::string> labels = lawComponentLabels(model);
  for (int q = 0; q < ref.force.cols(); ++q) out[labels[q]] = column(ref.force, q);
  return out;
}

nlohmann::json simulationJson(const app::Simulation& s, bool trajectory) {
  nlohmann::json out = referenceJson(s.model(), s.reference);
  out["scene"] = s.scene.name;
  out["omega"] = s.model().omega;
  if (trajectory) out["trajectory"] = referenceTrajectoryJson(s.model(), s.reference);
  return out;
}

nlohmann::json comparisonJson(const app::Comparison& c) {
  const HbModel& model = c.model();
  nlohmann::json out;
  out["scene"] = c.hb.scene.name;
  out["omega"] = model.omega;
  out["harmonics"] = model.basis.count();
  out["hb"] = {{"converged", c.hb.result.converged()},
               {"termination", terminationName(c.hb.result.termination)},
               {"residual_norm", c.hb.result.final_norm},
               {"seconds", c.hb.result.seconds}};
  out["reference"] = referenceJson(model, c.reference);
  nlohmann::json errors = nlohmann::json::array();
  for (const auto& e : c.errors)
    errors.push_back({{"channel", e.label}, {"relative_l2", e.relative_l2}, {"relative_l2_velocity", e.relative_l2_rate},
                      {"relative_max_abs", e.relative_max_abs}, {"first_harmonic_error", e.first_harmonic_error},
                      {"max_abs_hb", e.max_abs_hb}, {"max_abs_reference", e.max_abs_reference}});
  out["errors"] = errors;
  return out;
}

void writeReferenceText(std::ostream& out, const HbModel& model, const TimeReference& ref) {
  out << "time reference: " << (ref.periodic ? "periodic" : "NOT periodic") << " after " << ref.periods
      << " periods (change " << ref.periodicity_error << "), h = " << ref.step << " (" << ref.steps_per_period
      << " steps per period), " << ref.seconds << " s\n";
  for (int i = 0; i < model.structure.dofs(); ++i)
    out << "  max|" << dofLabel(model, i) << "| = " << ref.displacement.col(i).cwiseAbs().maxCoeff() << "\n";
  const std::vector<std::string> labels = lawComponentLabels(model);
  for (int q = 0; q < ref.force.cols(); ++q)
    out << "  max|" << labels[q] << "| = " << ref.force.col(q).cwiseAbs().maxCoeff() << "\n";
}

void writeSimulationText(std::ostream& out, const app::Simulation& s) {
  out << s.scene.name << " at omega = " << s.model().omega << "\n";
  writeReferenceText(out, s.model(), s.reference);
}

void writeComparisonText(std::ostream& out, const app::Comparison& c) {
  const HbModel& model = c.model();
  out << c.hb.scene.name << " at omega = " << model.omega << ", H = " << model.basis.count() << "\n"
      << "harmonic balance: " << c.hb.result.summary() << "\n";
  writeReferenceText(out, model, c.reference);
  out << "errors (HB vs reference):\n";
  for (const auto& e : c.errors)
    out << "  " << e.label << ": L2 " << e.relative_l2
        << (e.label[0] == 'x' ? ", velocity L2 " + std::to_string(e.relative_l2_rate) : "") << ", max|.| "
        << e.max_abs_hb << " vs " << e.max_abs_reference << " (" << e.relative_max_abs << "), first harmonic "
        << e.first_harmonic_error << "\n";
}

}  // namespace eqhb::output
