// Work–precision against the exact periodic orbits: per scene, curves of
// (median time per solve, error against the exact orbit) with H varying
// along each curve (N following H) and the law form, the ρ policy, the
// system, the backend and the variant fixed; and the convergence rate in H
// of each curve (least-squares slope of log error against log H).
#pragma once

#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "exact_reference.h"

namespace eqhb::bench {

struct PrecisionScene {
  std::string file;    // problems/FILE
  double omega = 0.0;
  double restitution = 0.0;  // Newton's impact coefficient of the exact orbit (contact)
  double rho = 1.0;    // the scene file's ρ, what the fixed policy keeps
  // > 0: the reference is the law's alternating frequency–time solution at
  // this H instead of the exact orbit (a model too large to shoot in the
  // study's time: beam-damper-elastic's 120 DOFs); the ladder then stops at
  // `largest_harmonics` and only the own dogleg's forms run (no shooting).
  int reference_harmonics = 0;
  int largest_harmonics = 0;  // 0: the whole ladder
  std::string label() const;  // "friction-1d ω=0.4" (", e=1" for contact)
};

// ρ along a curve: the scene's (fixed), ρ·H₀/H with H₀ the first H of the
// ladder (scaled), or balanced on the solution at H₀ (adaptive: ρ = max|v| /
// max|λ| for friction, max p / max gap for contact, so that both arguments of
// the law's min/max or projection are of one size); none for laws without ρ.
enum class RhoPolicy { kFixed, kScaled, kAdaptive, kNone };
const char* rhoPolicyName(RhoPolicy policy);

struct PrecisionCurve {
  std::string form;  // the law's form, "" when it has none (cubic)
  RhoPolicy rho = RhoPolicy::kFixed;
  bool condensed = true;
  std::string backend = "dogleg";
  // Harmonic balance followed by shooting (orbit_refinement.h): the error is
  // that of the exact orbit's truncation on the same harmonics.
  bool refine = false;
  // With refine: harmonic balance only at H₀ (the first H of the ladder),
  // then shooting, the orbit projected on each H of the ladder.
  bool coarse_start = false;
  std::string name() const;  // "minmax, ρ fixed, condensed, dogleg" (+ " + shooting" (" from H0"))
};

struct PrecisionPoint {
  std::string scene;
  PrecisionCurve curve;
  int harmonics = 0, samples = 0;
  double rho = 0.0;  // 0 when the law has none
  bool converged = false;
  std::string failure;
  double seconds = 0.0;  // median over the repeats; failed solves keep their time
  int iterations = 0;
  double sup_error = NAN, max_abs_error = NAN;
};

// The curves measured on a scene: every exact form × ρ policy on the own
// dogleg and the condensed system (the full one for contact, which the
// dogleg solves there), the scene's first form at the fixed ρ on the other
// backends and systems, harmonic balance followed by shooting per form, and
// shooting from H₀ projected on every H for the first form.
// A scene with a harmonic-balance reference gets the own dogleg's forms and
// the AFT form only.
std::vector<PrecisionCurve> curvesFor(const HbModel& model, const std::vector<std::string>& backends,
                                      bool harmonic_balance_reference = false);

// One curve over the ladder of H: each point solved by continuation in H
// from min(H, H₀) (H₀ = harmonics.front()), timed `repeats` times (once
// when a solve takes more than a second).
std::vector<PrecisionPoint> runCurve(const PrecisionScene& scene, const PrecisionCurve& curve,
                                     const std::vector<int>& harmonics, const ExactOrbit& exact, int repeats);

struct RateFit {
  int points = 0;                 // converged points above rounding
  double sup = NAN, max_abs = NAN;  // −slope of log error vs log H
};
// Least squares over the converged points whose error is above 1e-10.
RateFit fitRate(const std::vector<PrecisionPoint>& points);

}  // namespace eqhb::bench
