#include "eqhb/output/orbit_json.h"

#include <vector>

#include "eqhb/harmonic_balance/hb_solution.h"

namespace eqhb::output {

namespace {
std::vector<double> column(const Eigen::MatrixXd& m, Eigen::Index j) {
  const Eigen::VectorXd c = m.col(j);
  return std::vector<double>(c.data(), c.data() + c.size());
}
}  // namespace

nlohmann::json flowSamplesJson(const HbModel& model, const orbits::FlowSamples& samples) {
  nlohmann::json out = {{"t", samples.times}};
  for (Eigen::Index i = 0; i < samples.displacement.cols(); ++i) {
    out[dofLabel(static_cast<int>(i))] = column(samples.displacement, i);
    out["v" + std::to_string(i + 1)] = column(samples.velocity, i);
  }
  const std::vector<std::string> labels = lawComponentLabels(model);
  for (Eigen::Index q = 0; q < samples.force.cols(); ++q) out[labels[q]] = column(samples.force, q);
  return out;
}

nlohmann::json orbitJson(const app::Orbit& o, bool trajectory) {
  const HbModel& model = o.model();
  const orbits::ShootingResult& orbit = o.orbit;
  nlohmann::json out;
  out["scene"] = o.hb.scene.name;
  out["omega"] = model.omega;
  out["period"] = o.period();
  out["restitution"] = o.restitution;
  out["from_hb"] = {{"harmonics", model.basis.count()}, {"converged", o.hb.result.converged()},
                    {"residual_norm", o.hb.result.final_norm}};
  out["converged"] = orbit.converged;
  if (!orbit.converged) out["failure"] = orbit.failure;
  out["period_residual"] = orbit.period_residual;
  out["tolerance"] = o.tolerance;
  out["iterations"] = orbit.iterations;
  out["flow_evaluations"] = orbit.flow_evaluations;
  out["start_time"] = orbit.start_time;
  out["state"] = std::vector<double>(orbit.state.data(), orbit.state.data() + orbit.state.size());
  nlohmann::json dofs = nlohmann::json::array();
  for (int i = 0; i < orbit.max_abs.size(); ++i) dofs.push_back({{"dof", i + 1}, {"name", dofLabel(model, i)}, {"max_abs", orbit.max_abs[i]}});
  out["dofs"] = dofs;
  // Floquet multipliers belong to an orbit: null when none was found.
  nlohmann::json multipliers = nlohmann::json::array();
  for (int k = 0; k < orbit.multipliers.size(); ++k)
    multipliers.push_back({orbit.multipliers[k].real(), orbit.multipliers[k].imag()});
  out["multipliers"] = orbit.converged ? multipliers : nlohmann::json(nullptr);
  out["spectral_radius"] = orbit.converged ? nlohmann::json(orbit.spectral_radius) : nlohmann::json(nullptr);
  out["stable"] = orbit.converged ? nlohmann::json(orbit.stable) : nlohmann::json(nullptr);
  out["events"] = orbit.events;
  out["seconds"] = orbit.seconds;
  out["seconds_per_orbit"] = orbit.seconds_per_orbit;
  if (trajectory && orbit.converged && o.samples) out["trajectory"] = flowSamplesJson(model, *o.samples);
  return out;
}

void writeOrbitText(std::ostream& out, const app::Orbit& o) {
  const HbModel& model = o.model();
  const orbits::ShootingResult& orbit = o.orbit;
  out << o.hb.scene.name << " at omega = " << model.omega << ", restitution " << o.restitution
      << ", from harmonic balance H = " << model.basis.count() << "\n"
      << (orbit.converged ? "periodic orbit" : "NOT converged: " + orbit.failure) << ", period residual "
      << orbit.period_residual << " after " << orbit.iterations << " Newton steps, " << orbit.seconds << " s ("
      << orbit.seconds_per_orbit << " s per orbit)\n";
  for (int i = 0; i < orbit.max_abs.size(); ++i) out << "  max|" << dofLabel(model, i) << "| = " << orbit.max_abs[i] << "\n";
  if (!orbit.converged) return;
  out << "  multipliers:";
  for (int k = 0; k < orbit.multipliers.size(); ++k)
    out << " " << orbit.multipliers[k].real() << (orbit.multipliers[k].imag() >= 0 ? "+" : "")
        << orbit.multipliers[k].imag() << "i";
  out << "\n  " << (orbit.stable ? "stable" : "unstable") << " (spectral radius " << orbit.spectral_radius
      << ")\n  events per period:";
  for (const auto& [kind, count] : orbit.events) out << " " << kind << " " << count;
  out << "\n";
}

}  // namespace eqhb::output
