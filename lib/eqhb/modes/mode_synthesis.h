// Single nonlinear mode synthesis: the forced response near the resonance
// of a mode, read off its backbone. At modal amplitude a the structure is
// taken to move as the mode there (its fundamental shape ψ(a) = x̂₁ / a,
// frequency ω(a) and damping ratio ζ(a), which holds every dissipation:
// the structure's damping and its laws'), now at the forcing frequency Ω,
// with the forcing's work on the mode balancing what it dissipates; the
// projection of the fundamental's balance on ψ gives
//   (ω² − Ω² + 2iζωΩ) m a = ψᴴ F̂,   m = ψᴴ M ψ,
// with F̂ = F_c − i F_s the forcing's first harmonic (x = Re{x̂ e^{iΩt}}).
// Its modulus, with r = |ψᴴ F̂| / (m a), is a quadratic in Ω²:
//   Ω² = ω² (1 − 2ζ²) ± √(r² − 4ζ² ω⁴ (1 − ζ²)),
// two frequencies (below and above the backbone) up to the amplitude where
// the root vanishes: the synthesised peak. The response at (Ω, a) is the
// mode's (max|x| per DOF at a, its static state included).
// (Krack, "Nonlinear modal analysis of nonconservative systems: extension
// of the periodic motion concept", Computers & Structures 154, 2015.)
#pragma once

#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/modes/backbone.h"

namespace eqhb {

struct SynthesisPoint {
  double omega = 0.0;      // Ω, the forcing frequency
  double amplitude = 0.0;  // the backbone's modal amplitude a
  bool upper = false;      // on the branch above the backbone's frequency
  std::vector<double> max_abs;  // per DOF: the mode's at a
};

struct ModeSynthesis {
  // Along the curve: the lower branch in the backbone's order (up in
  // amplitude), then the upper branch in reverse (back down).
  std::vector<SynthesisPoint> points;
  // The synthesised peak: where the root vanishes, interpolated linearly in
  // a between the backbone's amplitudes on either side (ω, ζ and max|x|
  // too), and `closed`; when the backbone ends below it, its last
  // amplitude with a real Ω, and not `closed` (a larger `to` is needed).
  double peak_amplitude = 0.0, peak_omega = 0.0;
  std::vector<double> peak_max_abs;  // per DOF
  bool closed = false;
  // No amplitude of the backbone has a real Ω, the first already beyond the
  // peak: the forcing drives this mode only below `from` (a forcing nearly
  // orthogonal to the mode).
  bool peak_below_from = false;
};

// F̂ per DOF from `forced`'s harmonic-1 loads (its other loads do not
// enter); throws InputError naming "forcing" when it has none.
Eigen::VectorXcd synthesisForcing(const HbModel& forced);

// `forced`: the scene's model with its loads. Throws as synthesisForcing.
ModeSynthesis synthesizeForcedResponse(const HbModel& forced, const Backbone& backbone);

}  // namespace eqhb
