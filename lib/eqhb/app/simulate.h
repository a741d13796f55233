// The time-domain reference of a scene (`eqhb simulate`, Python's
// eqhb.simulate) and a harmonic-balance solve against it (`eqhb compare`,
// eqhb.compare): Moreau–Jean integration to the periodic steady state with
// the scene's [time_reference] defaults, from rest or from the
// harmonic-balance solution.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "eqhb/app/scene_settings.h"
#include "eqhb/app/solution.h"
#include "eqhb/app/solve_options.h"
#include "eqhb/references/time_integrator.h"

namespace eqhb::app {

// Each setting left unset takes the scene's [time_reference] value, else
// TimeOptions' default.
struct TimeSettings {
  std::optional<double> step;                // requested h > 0 (adjusted to divide the period)
  std::optional<int> periods;                // most periods, >= 1
  std::optional<double> theta;               // of the scheme, in [0.5, 1]
  std::optional<double> periodic_tolerance;  // relative change of the period-start state
  double max_seconds = 0.0;                  // wall-clock limit of the integration (0: none)
  double restitution = 0.0;                  // Newton impact coefficient of contact laws
};

// The options a run on `scene` uses: defaults, then the scene's, then the settings given.
TimeOptions timeOptionsFor(const Scene& scene, const TimeSettings& settings);

struct SimulateOptions {
  TimeSettings time;
  bool from_hb = false;  // start from the harmonic-balance solution (which must converge) instead of rest
  SolveOptions hb;       // that solve
  Eigen::VectorXd initial;  // else start from these coefficients [x; λ] (full layout); empty: rest
};

struct Simulation {
  Scene scene;
  TimeOptions options;       // as used
  TimeReference reference;
  std::optional<HbRun> hb;   // the start, with from_hb
  const HbModel& model() const { return scene.model; }
};

// Called once the options are known, before the integration: a per-period
// callback (progress) or an empty one.
using PeriodObserver = std::function<PeriodCallback(const Scene& scene, const TimeOptions& options)>;

// Throws InputError for bad options (naming the field) and, with from_hb, a
// solve that did not converge (std::runtime_error). Not settling is a status
// (reference.periodic).
Simulation simulate(const SceneSettings& scene, const SimulateOptions& options,
                    const PeriodObserver& observer = PeriodObserver());

struct CompareOptions {
  TimeSettings time;
  bool from_rest = false;  // start the reference from rest (default: from the harmonic-balance solution)
  SolveOptions hb;
};

struct Comparison {
  HbRun hb;                          // the solve compared (its last iterate when not converged)
  TimeOptions options;               // of the reference
  TimeReference reference;
  std::vector<ChannelError> errors;  // per DOF then per law component, by label
  const HbModel& model() const { return hb.scene.model; }
  bool succeeded() const { return hb.result.converged() && reference.periodic; }
};

Comparison compare(const SceneSettings& scene, const CompareOptions& options,
                   const PeriodObserver& observer = PeriodObserver());

}  // namespace eqhb::app
