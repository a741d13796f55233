#include "eqhb/output/backbone_writers.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "eqhb/round_trip.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/output/solution_json.h"
#include "eqhb/output/solve_effort_json.h"

namespace eqhb::output {

namespace {
nlohmann::json pointJson(const HbModel& model, const BackbonePoint& p) {
  nlohmann::json out = solveEffortJson(p);
  out["amplitude"] = p.amplitude;
  out["converged"] = p.converged;
  if (!p.converged) return out;
  out["omega"] = p.omega;
  out["xi"] = p.xi;
  out["damping_ratio"] = p.damping_ratio;
  out["dissipated_energy"] = p.dissipated_energy;
  out["max_abs"] = p.max_abs;
  out["channels"] = channelsJson(model, summarize(model, p.full));
  return out;
}
}  // namespace

nlohmann::json backboneJson(const app::ModesRun& run) {
  const Backbone& b = run.backbone;
  HbModel model = run.scene.model;
  model.structure.loads.clear();
  nlohmann::json points = nlohmann::json::array();
  for (const BackbonePoint& p : b.points) points.push_back(pointJson(model, p));
  nlohmann::json folds = nlohmann::json::array();
  for (const BackboneFold& f : b.folds)
    folds.push_back({{"amplitude", f.amplitude}, {"omega", f.omega}, {"damping_ratio", f.damping_ratio}});
  const std::vector<double> shape(b.start.shape.data(), b.start.shape.data() + b.start.shape.size());
  std::vector<std::string> labels;
  for (int i = 0; i < model.structure.dofs(); ++i) labels.push_back(dofLabel(model, i));
  return {{"scene", run.scene.name},
          {"mode", run.options.mode},
          {"branch", branchName(b.branch)},
          {"system", b.condensed ? "condensed" : "full"},
          {"solver", run.solver},
          {"from", run.options.from},
          {"to", run.options.to},
          {"dof_labels", labels},
          {"linear_mode", {{"omega", b.start.omega}, {"damping_ratio", b.start.damping_ratio}, {"shape", shape}}},
          {"complete", b.complete()},
          {"failed_points", b.failed_points},
          {"folds", folds},
          {"stop", b.stop.why.empty() ? nlohmann::json(nullptr)
                                      : nlohmann::json{{"why", b.stop.why},
                                                       {"amplitude", b.stop.amplitude},
                                                       {"omega", b.stop.omega},
                                                       {"damping_ratio", b.stop.damping_ratio}}},
          {"seconds", b.seconds},
          {"points", points}};
}

void writeBackboneCsv(std::ostream& out, const app::ModesRun& run) {
  const int n = run.scene.model.structure.dofs();
  out << "amplitude,omega,damping_ratio,xi,dissipated_energy";
  for (int i = 0; i < n; ++i) out << ",max_abs_" << dofLabel(run.scene.model, i);
  out << ",converged,termination,iterations\n";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const BackbonePoint& p : run.backbone.points) {
    out << formatRoundTrip(p.amplitude);
    for (double v : {p.omega, p.damping_ratio, p.xi, p.dissipated_energy}) out << "," << formatRoundTrip(p.converged ? v : nan);
    for (int i = 0; i < n; ++i) out << "," << formatRoundTrip(p.converged ? p.max_abs[i] : nan);
    out << "," << (p.converged ? 1 : 0) << "," << p.termination << "," << p.iterations << "\n";
  }
}

void writeBackboneText(std::ostream& out, const app::ModesRun& run) {
  const Backbone& b = run.backbone;
  char line[256];
  std::snprintf(line, sizeof line, "%s mode %d (%s branch, %s system): linear omega = %.8g, zeta = %.6g; %d points, %d failed, %.3g s\n",
                run.scene.name.c_str(), run.options.mode, branchName(b.branch), b.condensed ? "condensed" : "full", b.start.omega, b.start.damping_ratio,
                static_cast<int>(b.points.size()), b.failed_points, b.seconds);
  out << line;
  for (const BackboneFold& f : b.folds) {
    std::snprintf(line, sizeof line, "fold: the backbone turns back at amplitude %.5g (omega = %.8g, zeta = %.6g)\n",
                  f.amplitude, f.omega, f.damping_ratio);
    out << line;
  }
  if (!b.stop.why.empty()) {
    std::snprintf(line, sizeof line, "the path %s, at amplitude %.5g (omega = %.8g, zeta = %.6g)\n",
                  b.stop.why.c_str(), b.stop.amplitude, b.stop.omega, b.stop.damping_ratio);
    out << line;
  }
  out << "   amplitude        omega         zeta   energy/cycle\n";
  for (const BackbonePoint& p : b.points) {
    if (p.converged)
      std::snprintf(line, sizeof line, "%12.5g %12.8g %12.6g %14.6g\n", p.amplitude, p.omega, p.damping_ratio,
                    p.dissipated_energy);
    else
      std::snprintf(line, sizeof line, "%12.5g   not converged: %s\n", p.amplitude, p.termination.c_str());
    out << line;
  }
}

}  // namespace eqhb::output
