// The exact periodic orbit of a scene by shooting, as every interface runs it
// (`eqhb shoot`, Python's eqhb.shoot): a harmonic-balance solve of the scene
// with the solve's own start and fallbacks (app::solveHarmonicBalance), then
// Newton on the period map from it, with Floquet multipliers and events.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "eqhb/app/scene_settings.h"
#include "eqhb/app/solution.h"
#include "eqhb/app/solve_options.h"
#include "eqhb/orbits/default_restitution.h"
#include "eqhb/orbits/piecewise_linear_flow.h"
#include "eqhb/orbits/shooting.h"

namespace eqhb::app {

struct ShootOptions {
  // The harmonic-balance start: solver, fallback, limits. Its time_limit
  // bounds the whole run: the start, then shooting with what is left.
  SolveOptions hb;
  std::optional<int> from_hb;  // H of the start (the scene's when unset), >= 1
  // Newton impact coefficient e of contact laws, in [0, 1]; by default the
  // one harmonic balance approaches (orbit_refinement.h)
  double restitution = orbits::kHarmonicBalanceRestitution;
  double tolerance = orbits::ShootingOptions{}.tolerance;  // relative period residual, > 0
  int max_iterations = orbits::ShootingOptions{}.max_iterations;  // Newton steps, >= 1
  bool trajectory = false;     // sample one period of the orbit on the model's N instants

  // False with a message naming the field, its value and the rule.
  bool isValid(std::string* why) const;
};

// The orbit and the start it came from.
struct Orbit {
  HbRun hb;                                // the harmonic-balance start (scene at the start's H)
  std::unique_ptr<orbits::Flow> flow;
  orbits::ShootingResult orbit;
  double restitution = 0.0;
  double tolerance = 0.0;
  // One period from orbit.start_time on N instants (trajectory asked and the
  // flow integrated it).
  std::optional<orbits::FlowSamples> samples;

  const HbModel& model() const { return hb.scene.model; }
  double period() const { return flow->period(); }
};

// Called after the harmonic-balance start, before shooting, with the scene
// and the options shooting runs with: a per-Newton-step callback (progress)
// or an empty one.
using ShootingObserver =
    std::function<orbits::ShootingProgress(const Scene& scene, const orbits::ShootingOptions& options)>;

// Throws InputError for laws without an exact flow, a bad restitution or bad
// options (before any solve), TimeLimitReached when the start runs out of
// time. A start that did not converge is a warning (hb.warnings); shooting
// that does not converge is a status (orbit.converged).
Orbit shoot(const SceneSettings& scene, const ShootOptions& options,
            const ShootingObserver& observer = ShootingObserver());

}  // namespace eqhb::app
