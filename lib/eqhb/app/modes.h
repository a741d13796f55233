// The nonlinear mode of a scene as every interface computes it (`eqhb
// modes`, Python's eqhb.modes): the scene's structure and laws without its
// loads, the linearised structure's mode K as the start, and the backbone
// in modal amplitude (modes/backbone.h) by the chosen backend.
#pragma once

#include <optional>
#include <string>

#include "eqhb/app/scene_settings.h"
#include "eqhb/modes/backbone.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/solvers/solver.h"

namespace eqhb::app {

struct ModesOptions {
  int mode = 1;  // K, by increasing frequency of the linearised structure, >= 1
  // "held": from mode K of the structure with its laws linearised about rest
  // (sticking friction holds its DOF), up in amplitude. "sliding": from mode
  // K of the structure without its laws, at `to`, down in amplitude (every
  // friction contact sliding). "auto": sliding when the scene's [sweep]
  // range holds the free structure's mode K and not the held one's (the
  // forced resonance the scene is about lies on the sliding branch, as
  // beam-damper's), held otherwise.
  std::string branch = "auto";
  // Modal amplitude range φᵀ M x̂₁, both > 0, from < to. Unset on a sliding
  // branch: from 2 to 10³ times the amplitude a_f at which the friction
  // contacts, all sliding on the free mode, alone would give ζ = 1
  // (ζ_f = a_f / a: 4 Σ μN |w·φ| a a cycle against 2π ω² a² ζ), that is from
  // ζ_f = 0.5 to 10⁻³. Unset on a held branch: 10⁻² and
  // 10³ times the amplitude at which the linear mode's reaction at a law
  // reaches the law's force level (a friction law's slip onset; a friction
  // contact pressed by a preload: the static state's μN), so that
  // the range runs from well below it to well above; without a force level,
  // the scene's length scale (problem_scales.h) over max|φ|. About a static
  // state with pressed contacts, `to` is lowered to 3 times where the first
  // would open on the linear mode (not below 10 times the onset): a joint's
  // micro- and macroslip lie below, separation (far costlier) above.
  std::optional<double> from, to;
  int points = 50;                 // >= 2, evenly spaced in log a
  double backbone_time_limit = 0.0;  // seconds for the whole backbone, 0 = none
  // The caller synthesises a forced response from the backbone (synthesis.h):
  // a scene without first-harmonic forcing is refused before any solve.
  bool synthesis = false;
  std::string solver = "dogleg";   // a registered backend
  // The condensed mode system (the law forces alone; every A_k factored at
  // each new ω and ξ) instead of the full one (BackboneOptions::condensed).
  bool condensed = false;
  SolverOptions solver_options;    // tolerance, limits, backend settings

  // False with a message naming the field, its value and the rule.
  bool isValid(std::string* why) const;
};

struct ModesRun {
  Scene scene;
  std::string solver;
  BackboneOptions options;  // as run: the range chosen when not given
  Backbone backbone;
};

// Throws InputError naming the option or the scene's field (a mode above
// the structure's count, an amplitude range <= 0 or not finite).
// `progress` is called at each amplitude recorded, in the path's order.
ModesRun modes(const SceneSettings& scene, const ModesOptions& options, const BackboneProgress& progress = nullptr);

}  // namespace eqhb::app
