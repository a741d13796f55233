// The time-domain reference of truth (spec §4): nonsmooth time stepping of
//   M ẍ + C ẋ + K x = f(t) + Σ W_l s_l λ_l,
// Moreau–Jean θ-method with the EXACT law solved at every step (no
// regularisation): with Ŵ = M + hθC + h²θ²K,
//   Ŵ v⁺ = M v + h f_θ − h(1−θ) C v − h K x − h²θ(1−θ) K v + h Σ W_l s_l λ_l,
//   x⁺   = x + h (θ v⁺ + (1−θ) v),
// each law's force λ_l held over the step and found by the law's own
// local solver (Law::solveStep); several laws are coupled by block
// Gauss–Seidel. θ = 1 is implicit Euler (O(h)), θ = ½ the midpoint rule.
//
// The step is adjusted so that a period holds a whole number of steps;
// integration runs period by period until two consecutive period-start
// states agree (relative tolerance) or the period limit is reached, and the
// last period is kept, with its Fourier coefficients on the model's basis.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb {

// Most steps in one period (the last period is kept sample by sample).
inline constexpr double kMaxStepsPerPeriod = 1e7;

struct TimeOptions {
  double step = 1e-4;              // requested h > 0; the used one divides T
  double theta = 0.5;              // in [½, 1]
  int max_periods = 5000;          // >= 1
  double periodic_tolerance = 1e-9;  // relative change of the period-start state
  double restitution = 0.0;        // Newton impact coefficient e in [0, 1]
  // Wall-clock limit in seconds (0: none), checked after every period: a
  // run that has not settled by then stops with timed_out set.
  double max_seconds = 0.0;
  // Throws InputError naming the field.
  void validate() const;
};

struct TimeReference {
  bool periodic = false;       // the tolerance was met
  int periods = 0;             // periods integrated
  double step = 0.0;           // the step used
  int steps_per_period = 0;
  double periodicity_error = 0.0;  // last relative change
  double seconds = 0.0;
  bool timed_out = false;      // stopped by max_seconds before settling
  // Last period, sample i at t = iT/steps_per_period: columns are DOFs
  // (displacement, velocity) or law components (force λ over the step
  // ending at that instant).
  Eigen::MatrixXd displacement, velocity, force;
  Eigen::VectorXd coefficients;  // [x; λ] projected on the model's basis
};

// Called after every period with the periods done and the relative change
// of the period-start state (for progress on a long run).
using PeriodCallback = std::function<void(int periods, double change)>;

// Integrates from `initial_full` (coefficients [x; λ] whose state at t = 0
// starts the run, e.g. a harmonic-balance solution) or from rest if empty.
TimeReference integrateToSteadyState(const HbModel& model, const TimeOptions& options,
                                     const Eigen::VectorXd& initial_full = Eigen::VectorXd(),
                                     const PeriodCallback& on_period = PeriodCallback());

// Distances between a harmonic-balance solution and a reference. Each is
// relative to the reference channel's own size, floored at kChannelFloor
// times the largest channel of the same kind (displacements, velocities,
// forces): a channel that stays near zero is not divided by its noise.
constexpr double kChannelFloor = 1e-3;
struct ChannelError {
  std::string label;
  double relative_l2 = 0.0;            // ‖hb − ref‖₂ / ‖ref‖₂ over the period
  double relative_l2_rate = 0.0;       // the same for the velocity (DOFs only)
  double relative_max_abs = 0.0;       // |max|hb| − max|ref|| / max|ref|
  double first_harmonic_error = 0.0;   // |A₁(hb) − A₁(ref)| / A₁(ref), A₁ = |(a₁, b₁)|
  double max_abs_reference = 0.0, max_abs_hb = 0.0;
};
std::vector<ChannelError> compareWithReference(const HbModel& model, const Eigen::VectorXd& hb_full,
                                               const TimeReference& reference);

}  // namespace eqhb
