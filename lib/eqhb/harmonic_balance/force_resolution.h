// Whether a law's force is resolved by the harmonics it is given: a
// diagnosis for the sweeps that stop or leave points unsolved.
//
// Why: a contact that lands or a slider that sticks puts a kink or a jump in
// the force, whose harmonics fall as k^-2 or k^-1; the middle of the
// spectrum then outweighs its top. Where the truncation cannot follow the
// law's events (a landing the contact law makes abrupt, an impulse-like
// force), the spectrum stops falling and rises toward the highest harmonic
// (Gibbs' ripple, the same at every H). Measured on contact-friction-2d at
// ω = 0.12: the top quarter of the normal force's harmonics is 1.8-4.7 times
// its second quarter at H = 20, 30 and 40, and at H = 40 its branch breaks
// into pieces between ω = 0.1266 and 0.1282 where no solve converges; on the
// shipped scenes' converged H = 40 curves the ratio stays below 1 elsewhere
// except on a few points of the damper and the lap joint.
#pragma once

#include <Eigen/Dense>

#include <optional>
#include <string>

#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb {

// A law component whose spectrum rises toward the truncation.
struct UnresolvedForce {
  int law = 0;           // index into model.laws
  int component = 0;     // the law's component
  double rise = 0.0;     // RMS amplitude of the top quarter of the harmonics / of the second quarter
  int top_from = 0, top_to = 0;        // harmonic numbers of the top quarter
  int middle_from = 0, middle_to = 0;  // and of the second quarter
};

// Bands compared need this many non-constant harmonics: a few harmonics
// tell nothing of a spectrum's trend.
constexpr int kFewestHarmonicsForResolution = 8;
// A top band below this fraction of the component's largest harmonic is
// round-off or a law at rest, whatever its trend.
constexpr double kNegligibleTop = 1e-3;

// The law component of `full` (FullSystem layout [x; λ]) whose top quarter
// of harmonics outweighs its second quarter the most (rise > 1), if any.
std::optional<UnresolvedForce> worstUnresolvedForce(const HbModel& model, const Eigen::VectorXd& full);

// One clause for a stop reason: "law 1's force (lambda1) is not resolved at
// H = 40 at omega = 0.126: its harmonics 31-40 are 4.7 times its harmonics
// 11-20 ..."; empty if no component of `full` rises.
std::string unresolvedForceNote(const HbModel& model, const Eigen::VectorXd& full);

}  // namespace eqhb
