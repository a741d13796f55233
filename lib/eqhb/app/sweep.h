// A frequency-response curve of a scene as every interface runs it (`eqhb
// sweep`, Python's eqhb.sweep): the range and steps (the scene's [sweep] and
// ContinuationOptions' defaults where not given), sequential or arclength
// continuation with the fallback chain, or an accuracy target's curve (H and
// ρ chosen at the first point, raised on the points whose estimate exceeds
// it, accuracy_sweep.h); then per-point error estimates and stability.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/accuracy/accuracy_sweep.h"
#include "eqhb/app/rho_candidates.h"
#include "eqhb/app/scene_settings.h"
#include "eqhb/app/solver_choice.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/stability/curve_stability.h"

namespace eqhb::app {

// Defaults are those of `eqhb sweep`. The backend, system, limits and
// fallbacks, stability, error estimates and an accuracy target per point
// (solver_choice.h), with:
struct SweepOptions : SolverChoice, SolutionChecks {
  std::optional<double> from, to;  // default: the scene's [sweep]
  bool arclength = false;          // pseudo-arclength (passes turning points); else a grid in ω
  // The grid step in ω, or the initial scaled arclength step; default
  // ContinuationOptions::defaultStep (a hundredth of the range, or 0.01).
  std::optional<double> step;
  // Default min(1e-6, step) and max(0.1, step) (ContinuationOptions).
  std::optional<double> min_step, max_step;
  int max_points = 20000;
  // Seconds for the whole sweep, its curve and what follows (0: none): the
  // curve stops between two points keeping those found (curve_stop.h), the
  // stability gets what is left.
  double curve_time_limit = 0.0;
  // Set from outside (a signal handler) to stop the same way; error
  // estimates and stability are then skipped.
  const std::atomic<bool>* stop_requested = nullptr;

  // False with a message naming the field, its value and the rule (the
  // options alone; the range against the scene is checked by planSweep).
  bool isValid(std::string* why) const;
};

// The sweep resolved against its scene: what will run, before any solve.
struct SweepPlan {
  SceneSettings settings;
  Scene scene;                      // with every setting applied
  SweepOptions options;
  ContinuationOptions continuation; // range, steps and limits resolved (fallbacks set by sweep)
  std::string solver_name;          // the backend's own name
  // Points of the sequential grid; 0 for arclength (not known in advance).
  int expectedPoints() const;
};

// Loads the scene and resolves the range and steps; throws InputError naming
// the option (from, to, step, min_step, max_step, stability, solver,
// fallback) or the scene's field.
SweepPlan planSweep(const SceneSettings& scene, const SweepOptions& options);

// Told of each point as the sweep finds it, and with an accuracy target of
// each point as it is checked.
struct SweepCallbacks {
  Progress point;
  Progress checked;
  std::function<void(int done, int total)> stability;  // after each point's stability
};

struct SweepResult {
  SweepPlan plan;
  Curve curve;
  HbModel model;  // the curve's discretisation (an accuracy target's choice)
  std::optional<CurveStability> stability;  // asked
  // With an accuracy target: the choice at the first point, the points not
  // met, the highest H and the time (its `curve` moved into `curve` above),
  // and the ρ candidates it chose from.
  std::optional<AccurateCurve> accurate;
  RhoCandidates rho;

  // The largest error estimate of a converged point (0: none).
  double largestEstimate() const;
  // Complete, no failed point, not empty, and the accuracy target met everywhere.
  bool succeeded() const;
};

SweepResult sweep(const SweepPlan& plan, const SweepCallbacks& callbacks = {});
SweepResult sweep(const SceneSettings& scene, const SweepOptions& options, const SweepCallbacks& callbacks = {});

}  // namespace eqhb::app
