#include "exact_reference.h"

#include <algorithm>

#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/references/time_integrator.h"

namespace eqhb::bench {

HbModel onHarmonics(HbModel model, int harmonics) {
  model.basis = HarmonicSet(model.basis.kind(), harmonics);
  model.samples = std::max(model.samples, 8 * model.basis.highest() + 8);
  return model;
}

Eigen::VectorXd referenceHarmonicBalance(const HbModel& model, bool* converged) {
  auto solver = makeSolver("dogleg");
  SolverOptions options;
  options.residual_tolerance = 1e-10;
  options.max_iterations = 400;
  Eigen::VectorXd full;
  const bool condensed = suitsCondensedSystem(model.laws);
  const SolverResult r =
      solveByHarmonicContinuation(model, *solver, options, std::min(5, model.basis.count()), condensed, &full);
  if (converged) *converged = r.converged();
  return full;
}

ExactOrbit exactOrbit(const HbModel& model, double restitution, const Eigen::VectorXd& hb) {
  ExactOrbit out;
  const auto flow = orbits::makeFlow(model, restitution);
  out.orbit = orbits::shootFromHarmonicBalance(*flow, model, hb, orbits::ShootingOptions());
  const double t0 = out.orbit.start_time;
  if (!out.orbit.converged) return out;
  orbits::FlowSamples samples;
  const int count = 4096;
  for (int s = 0; s < count; ++s) samples.times.push_back(t0 + flow->period() * s / count);
  if (!flow->integrate(out.orbit.state, t0, flow->period(), false, &samples).ok) return out;
  out.times = samples.times;
  out.displacement = samples.displacement;
  return out;
}

ExactOrbit harmonicBalanceOrbit(const HbModel& model, const Eigen::VectorXd& full, bool converged) {
  ExactOrbit out;
  out.orbit.converged = converged;
  if (!converged) {
    out.orbit.failure = "the reference harmonic balance did not converge";
    return out;
  }
  const int n = model.structure.dofs(), count = 4096;
  const double period = 2.0 * M_PI / model.omega;
  out.displacement.resize(count, n);
  for (int s = 0; s < count; ++s) {
    out.times.push_back(period * s / count);
    out.displacement.row(s) = orbits::harmonicState(model, full, out.times.back()).head(n);
  }
  out.orbit.max_abs = peakDisplacements(model, full);
  return out;
}

SeriesError seriesError(const HbModel& model, const Eigen::VectorXd& full, const ExactOrbit& exact) {
  SeriesError out;
  const int n = model.structure.dofs();
  for (size_t s = 0; s < exact.times.size(); ++s) {
    const Eigen::VectorXd y = orbits::harmonicState(model, full, exact.times[s]);
    for (int i = 0; i < n; ++i) out.sup = std::max(out.sup, std::abs(y[i] - exact.displacement(s, i)));
  }
  out.sup /= exact.orbit.max_abs.maxCoeff();
  out.max_abs = worstRelativeDifference(peakDisplacements(model, full), exact.orbit.max_abs);
  return out;
}

double worstRelativeL2(const HbModel& model, const Eigen::VectorXd& full, const ExactOrbit& exact) {
  const int n = model.structure.dofs();
  const Eigen::Index count = static_cast<Eigen::Index>(exact.times.size());
  Eigen::MatrixXd hb(count, n);
  for (Eigen::Index s = 0; s < count; ++s) hb.row(s) = orbits::harmonicState(model, full, exact.times[s]).head(n);
  double largest = 0.0;
  for (int i = 0; i < n; ++i) largest = std::max(largest, exact.displacement.col(i).norm());
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, (hb.col(i) - exact.displacement.col(i)).norm() /
                                std::max({exact.displacement.col(i).norm(), kChannelFloor * largest, 1e-300}));
  return worst;
}

}  // namespace eqhb::bench
