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

struct BackboneOptions {
  int mode = 1;          // K: the linearised structure's K-th mode by frequency, >= 1
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
  std::vector<BackbonePoint> points;  // in the order of the path
  std::vector<BackboneFold> folds;
  BackboneStop stop;
  int failed_points = 0;
  bool complete() const { return failed_points == 0 && !points.empty(); }
  double seconds = 0.0;
};

using BackboneProgress = std::function<void(const BackbonePoint&, int index)>;

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
