#include "bench_truth.h"

#include <algorithm>
#include <iostream>
#include <sstream>

#include "bench_cases.h"
#include "eqhb/backends/registry.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"

namespace eqhb::bench {

Truth buildTruth(const std::filesystem::path& path, double step, int max_periods) {
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
  if (std::any_of(base.model.laws.begin(), base.model.laws.end(),
                  [](const AttachedLaw& l) { return l.law->type() == "signorini"; })) {
    bool converged = false;
    const Eigen::VectorXd hb = referenceHarmonicBalance(base.model, &converged);
    auto exact = std::make_shared<ExactOrbit>(exactOrbit(base.model, 1.0, hb));
    if (exact->ok()) {
      truth.exact = exact;
      if (converged) truth.truncation_error = worstRelativeL2(base.model, hb, *exact);
      truth.truncation_harmonics = base.model.basis.count();
    }
    std::cerr << base.name << ": exact orbit (e = 1) " << (exact->ok() ? "converged" : "NOT converged")
              << ", truncation error at H = " << base.model.basis.count() << ": " << truth.truncation_error << "\n";
    return truth;
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

TruthStatus truthStatus(const Truth& truth) {
  if (truth.exact)
    return {truth.scene, "exact orbit, e = 1", truth.exact->orbit.converged, 1, truth.exact->orbit.period_residual,
            truth.exact->orbit.seconds_per_orbit, true, truth.high.size() > 0};
  return {truth.scene, "time run", truth.reference.periodic, truth.reference.periods, truth.reference.periodicity_error,
          truth.reference.seconds, truth.has_reference, truth.high.size() > 0};
}

std::string truthTable(const std::vector<TruthStatus>& truths) {
  std::ostringstream truth_table;
  truth_table << "| scene | reference | periodic | periods | period-to-period change | seconds | used | 4x-H solution |\n"
              << "|---|---|---|---|---|---|---|---|\n";
  for (const auto& t : truths)
    truth_table << "| " << t.scene << " | " << t.kind << " | " << (t.periodic ? "periodic" : "not periodic") << " | "
                << t.periods << " | "
                << number(t.change) << " | " << number(t.seconds) << " | " << (t.used ? "yes" : "no") << " | "
                << (t.high ? "converged" : "not available") << " |\n";
  return truth_table.str();
}

}  // namespace eqhb::bench
