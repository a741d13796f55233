#include "eqhb/app/shoot.h"

#include <algorithm>

#include "eqhb/app/solve.h"
#include "eqhb/error.h"
#include "eqhb/orbits/smooth_flow.h"
#include "eqhb/solvers/deadline.h"

namespace eqhb::app {

bool ShootOptions::isValid(std::string* why) const {
  if (from_hb && *from_hb < 1) return refuseOption(why, "from_hb", std::to_string(*from_hb), "must be >= 1");
  return hb.isValid(why);
}

Orbit shoot(const SceneSettings& given_scene, const ShootOptions& o, const ShootingObserver& observer) {
  std::string why;
  if (!o.isValid(&why)) throw InputError(why);
  SceneSettings scene = given_scene;
  if (o.from_hb) scene.harmonics = *o.from_hb;
  orbits::ShootingOptions options;
  options.tolerance = o.tolerance;
  options.max_iterations = o.max_iterations;
  options.time_limit = o.hb.solver_options.time_limit;
  options.validate();
  const double time_limit = o.hb.solver_options.time_limit;
  // time_limit bounds the whole run: the harmonic-balance start (which
  // checks it itself), then shooting with what is left.
  const Deadline deadline(time_limit);
  Orbit out;
  out.restitution = o.restitution;
  // The flow first: unsupported laws and a bad restitution fail before any solve.
  out.flow = orbits::makeFlow(loadScene(scene).model, o.restitution);
  out.hb = solveHarmonicBalance(scene, o.hb);
  const HbModel& model = out.hb.scene.model;
  if (out.hb.result.termination == Termination::kTimeLimit)
    throw TimeLimitReached("time limit of " + formatNumber(time_limit) +
                           " s reached during the harmonic-balance start (" + out.hb.result.native_message + ")");
  if (!out.hb.result.converged())
    out.hb.warnings.push_back("the harmonic-balance start did not converge (" +
                              std::string(terminationName(out.hb.result.termination)) +
                              "); shooting from its last iterate");
  if (deadline.limited()) options.time_limit = std::max(deadline.remaining(), 1e-3);
  if (observer) options.progress = observer(out.hb.scene, options);
  out.tolerance = options.tolerance;
  out.orbit = orbits::shootFromHarmonicBalance(*out.flow, model, out.hb.full(), options);
  if (o.trajectory) {
    orbits::FlowSamples samples;
    const double t0 = out.orbit.start_time;
    for (int s = 0; s < model.samples; ++s) samples.times.push_back(t0 + out.period() * s / model.samples);
    if (out.flow->integrate(out.orbit.state, t0, out.period(), false, &samples).ok) out.samples = std::move(samples);
  }
  return out;
}

}  // namespace eqhb::app
