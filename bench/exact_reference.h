// The exact periodic orbit of a scene as the reference of truth (shooting
// from a harmonic-balance start), densely sampled, and the distance of any
// truncated Fourier series to it.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/orbits/shooting.h"

namespace eqhb::bench {

struct ExactOrbit {
  orbits::ShootingResult orbit;
  std::vector<double> times;     // t0 + iT/S
  Eigen::MatrixXd displacement;  // S x n
  bool ok() const { return orbit.converged && !times.empty(); }
};

// `model` on `harmonics` harmonics of its kind, with N >= 8 h_max + 8 samples.
HbModel onHarmonics(HbModel model, int harmonics);

// The harmonic-balance start of a reference orbit: `model` solved by
// continuation in H from min(5, H) on the own dogleg to ‖g‖ <= 1e-10 in at
// most 400 iterations, on the full system for contact (which the dogleg
// solves there). [x; λ]; whether it converged in `converged` if given.
Eigen::VectorXd referenceHarmonicBalance(const HbModel& model, bool* converged = nullptr);

// Shoots from `hb` (FullSystem layout on `model`) and samples 4096 instants.
ExactOrbit exactOrbit(const HbModel& model, double restitution, const Eigen::VectorXd& hb);

// A converged harmonic-balance solution `full` on `model` sampled as the
// reference (4096 instants, its peaks as max_abs), where shooting is out of
// reach; `converged` false gives a reference that is not ok().
ExactOrbit harmonicBalanceOrbit(const HbModel& model, const Eigen::VectorXd& full, bool converged);

struct SeriesError {
  double sup = 0.0;      // max over the samples and DOFs of |x − x_exact| / max|x_exact|
  double max_abs = 0.0;  // worst relative error of max_t|x_i| per DOF (error_estimate.h's measure)
};

// `full` on `model`'s basis against the exact orbit.
SeriesError seriesError(const HbModel& model, const Eigen::VectorXd& full, const ExactOrbit& exact);

// The benchmark's measure against the exact orbit: per DOF ‖x − x_exact‖₂ /
// ‖x_exact‖₂ over the orbit's samples (the DOF's norm floored at
// kChannelFloor times the largest DOF's, as against a time reference), the
// worst DOF.
double worstRelativeL2(const HbModel& model, const Eigen::VectorXd& full, const ExactOrbit& exact);

}  // namespace eqhb::bench
