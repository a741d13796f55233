#include "eqhb/app/simulate.h"

#include <stdexcept>

#include "eqhb/app/solve.h"
#include "eqhb/error.h"

namespace eqhb::app {

TimeOptions timeOptionsFor(const Scene& scene, const TimeSettings& t) {
  TimeOptions options;
  const TimeReferenceDefaults& d = scene.time_reference;
  options.step = t.step ? *t.step : d.step.value_or(options.step);
  options.theta = t.theta ? *t.theta : d.theta.value_or(options.theta);
  options.max_periods = t.periods ? *t.periods : d.periods.value_or(options.max_periods);
  options.periodic_tolerance =
      t.periodic_tolerance ? *t.periodic_tolerance : d.periodic_tolerance.value_or(options.periodic_tolerance);
  options.max_seconds = t.max_seconds;
  options.restitution = t.restitution;
  return options;
}

Simulation simulate(const SceneSettings& scene, const SimulateOptions& o, const PeriodObserver& observer) {
  Simulation out;
  out.scene = loadScene(scene);
  Eigen::VectorXd start = o.initial;
  if (start.size()) {
    const HbModel& model = out.scene.model;
    const Eigen::Index full_size =
        static_cast<Eigen::Index>(model.basis.size()) * (model.structure.dofs() + model.lawComponents());
    if (start.size() != full_size || !start.allFinite())
      throwInputError("initial", "(" + std::to_string(start.size()) + " values)",
                      "must be a finite full coefficient vector of " + std::to_string(full_size) + " values");
  }
  if (o.from_hb) {
    out.hb = solveHarmonicBalance(scene, o.hb);
    if (!out.hb->result.converged())
      throw std::runtime_error("from_hb: the harmonic-balance solve did not converge (" +
                               std::string(terminationName(out.hb->result.termination)) + ")");
    start = out.hb->full();
  }
  out.options = timeOptionsFor(out.scene, o.time);
  out.options.validate();
  const PeriodCallback on_period = observer ? observer(out.scene, out.options) : PeriodCallback();
  out.reference = integrateToSteadyState(out.scene.model, out.options, start, on_period);
  return out;
}

Comparison compare(const SceneSettings& scene, const CompareOptions& o, const PeriodObserver& observer) {
  Comparison out;
  out.hb = solveHarmonicBalance(scene, o.hb);
  if (!out.hb.result.converged())
    out.hb.warnings.push_back("the harmonic-balance solve did not converge (" +
                              std::string(terminationName(out.hb.result.termination)) +
                              "); errors refer to its last iterate");
  const Eigen::VectorXd hb = out.hb.full();
  out.options = timeOptionsFor(out.hb.scene, o.time);
  out.options.validate();
  const PeriodCallback on_period = observer ? observer(out.hb.scene, out.options) : PeriodCallback();
  out.reference =
      integrateToSteadyState(out.model(), out.options, o.from_rest ? Eigen::VectorXd() : hb, on_period);
  out.errors = compareWithReference(out.model(), hb, out.reference);
  return out;
}

}  // namespace eqhb::app
