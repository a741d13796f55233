// The forced response a nonlinear mode predicts (modes/mode_synthesis.h)
// beside the forced sweep across the same resonance, as `eqhb modes
// --synthesis` and Python's eqhb.modes(synthesis=True) give them: the user
// sees whether the mode alone is enough there.
#pragma once

#include <string>

#include "eqhb/app/modes.h"
#include "eqhb/app/sweep.h"
#include "eqhb/modes/mode_synthesis.h"

namespace eqhb::app {

struct SynthesisComparison {
  // From the backbone with modes added between its points from a quarter
  // to twice the peak's modal amplitude (refinement_points of them).
  ModeSynthesis synthesis;
  int refinement_points = 0;
  // Why no forced sweep was compared (empty when one was): the synthesised
  // curve does not close below the backbone's end.
  std::string not_compared;
  int dof = 0;  // 0-based: the DOF compared, the largest at the synthesised peak
  // The forced curve (the scene's settings, arclength) over the band where
  // the synthesised max|x_dof| is above half its peak and the linear mode's
  // frequency, widened by a quarter of its width on each side.
  Curve forced;
  double forced_seconds = 0.0;
  double forced_peak_omega = 0.0, forced_peak_amplitude = 0.0;  // its largest max|x_dof|
  // (synthesis − forced) / forced at the peak.
  double peak_amplitude_error = 0.0, peak_omega_error = 0.0;
  // The forced points above half its peak (A_f >= A_f,peak / 2), the width
  // in Ω they span, and the largest distance from one of them to the
  // synthesised curve in the plane (Ω / band_width, A / A_f,peak): 0.05 is
  // 5 % of the peak's height, or 5 % of the band's width in Ω, away. A
  // distance, not a difference at the same Ω: a bent resonance is steep or
  // turns back near its peak.
  int band_points = 0;
  double band_width = 0.0;
  double band_error = 0.0;
};

// Throws InputError naming "forcing" when the scene has no first-harmonic
// forcing. `modes`: the backend and limits of the added modes; `sweep`:
// those of the forced sweep.
SynthesisComparison compareWithForcedSweep(const SceneSettings& scene, const ModesRun& run, const ModesOptions& modes,
                                           SweepOptions sweep);

}  // namespace eqhb::app
