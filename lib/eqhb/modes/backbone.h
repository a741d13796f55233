// A nonlinear mode followed in modal amplitude (mode_system.h): from the
// linearised structure's mode K at the smallest amplitude (linear_modes.h),
// the path is continued in pseudo-arclength through (shape, ω, ξ, log a)
// (mode_path_system.h), which passes the folds where the backbone turns
// back in amplitude, and the mode is recorded at N amplitudes spaced evenly
// in log a, at each crossing of the path in the order of the path: between
// two folds an amplitude has three modes, all listed. An arclength step
// whose corrector fails is halved, up to max_halvings times in a row; the
// grid amplitudes a path that stops did not reach are failed points.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/modes/linear_modes.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// Which family a friction-damped structure's mode K belongs to. Its laws
// held (sticking friction holds its DOF) give one linear structure, its laws
// removed (every friction contact sliding) another, and mode K of the one
// need not become mode K of the other: beam-damper's held mode 1 (ω 57.5)
// turns, past its folds, towards the free beam's mode 2, while its forced
// resonance lies on the free beam's mode 1 with the dampers sliding.
enum class ModeBranch {
  kHeld,     // from the laws linearised about rest, up in amplitude
  kSliding,  // from the structure without its laws at `to`, down in amplitude
};

struct BackboneOptions {
  int mode = 1;          // K: the linearised structure's K-th mode by frequency, >= 1
  ModeBranch branch = ModeBranch::kHeld;
  // The condensed mode system (condensed_mode_system.h: the law forces
  // alone) instead of the full one; needs a law and a regular K.
  bool condensed = false;
  double from = 0.0;     // smallest modal amplitude, > 0 (modes.h chooses one when not given)
  double to = 0.0;       // largest, > from
  int points = 50;       // >= 2
  int max_halvings = 8;  // of a failed arclength step, in a row, >= 0
  // Seconds for the whole backbone, 0 = none (finite, >= 0): the path stops
  // there, saying so, and the amplitudes not reached are failed points.
  double time_limit = 0.0;
  // Throws InputError naming the field; `modes`: how many the structure has.
  void validate(int modes) const;
};

struct BackbonePoint {
  double amplitude = 0.0;  // modal: φᵀ M x̂₁ (the fundamental's projection)
  bool converged = false;
  std::string termination;
  int iterations = 0, residual_evaluations = 0, jacobian_evaluations = 0;
  double seconds = 0.0;
  double omega = 0.0, xi = 0.0;
  double damping_ratio = 0.0;        // ζ = ξ / (2ω)
  double dissipated_energy = 0.0;    // per cycle: ξ ∮ ẋᵀ M ẋ dt
  std::vector<double> max_abs;       // per DOF, over one period
  Eigen::VectorXd full;              // [x̂; λ̂]
};

// Where the path turns back in amplitude: the turn of the quadratic through
// the path points on either side of it.
struct BackboneFold {
  double amplitude = 0.0, omega = 0.0, damping_ratio = 0.0;
};

// Where and why a path stopped short of `to` (empty `why` when it did not).
struct BackboneStop {
  std::string why;
  double amplitude = 0.0, omega = 0.0, damping_ratio = 0.0;  // its last point
};

struct Backbone {
  LinearMode start;                  // the linear mode it started from
  ModeBranch branch = ModeBranch::kHeld;
  bool condensed = false;  // the system it was solved on
  // In the order of the path; a sliding branch's in increasing amplitude
  // (its path runs down from `to`).
  std::vector<BackbonePoint> points;
  std::vector<BackboneFold> folds;
  BackboneStop stop;
  int failed_points = 0;
  bool complete() const { return failed_points == 0 && !points.empty(); }
  double seconds = 0.0;
};

using BackboneProgress = std::function<void(const BackbonePoint&, int index)>;

// "held" or "sliding".
const char* branchName(ModeBranch branch);

// The linear modes a branch starts from, by increasing frequency: the
// structure's with its laws linearised about rest (or `at_rest`) for a held
// branch, without its laws for a sliding one.
std::vector<LinearMode> startingModes(const HbModel& model, ModeBranch branch,
                                      const StaticContactState* at_rest = nullptr);

// Throws InputError for bad options or a model without the fundamental, or
// when the solver rejects its options. `at_rest`: a preloaded scene's static
// state (Scene::at_rest), about which the mode vibrates: its loads stay
// applied, the linear mode is the structure's linearised there, and every
// start adds the static state's constant terms.
Backbone followBackbone(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                        const BackboneOptions& options, const BackboneProgress& progress = nullptr,
                        const StaticContactState* at_rest = nullptr);

// ξ ∮ ẋᵀ M ẋ dt over one period = ξ π ω Σ_{k>0} k² (x̂_cᵀ M x̂_c + x̂_sᵀ M x̂_s):
// what −ξ M ẋ feeds in, equal to what the structure and its laws dissipate.
double dissipatedEnergy(const HbModel& model, const Eigen::VectorXd& full, double omega, double xi);

}  // namespace eqhb
