// Periodic orbits of the forced system by shooting: Newton on the period
// map P(y0) = y(t0 + T; y0, t0), solving (Φ − I) δ = −(P(y0) − y0) with the
// monodromy Φ = ∂P/∂y0 (saltation matrices included at the events), with a
// backtracking line search on ‖P(y) − y‖. At the solution the Floquet
// multipliers are the eigenvalues of Φ: the orbit is asymptotically stable
// iff all lie strictly inside the unit circle. Newton does not care about
// stability, so unstable orbits are found as well.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <map>
#include <string>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/orbits/piecewise_linear_flow.h"

namespace eqhb::orbits {

// After every period-map evaluation: the Newton steps taken, the period-map
// evaluations so far and the best relative period residual.
using ShootingProgress = std::function<void(int iterations, int flow_evaluations, double residual)>;

struct ShootingOptions {
  // Relative period residual ‖P(y) − y‖∞ / ‖y‖∞ counted as periodic, > 0.
  double tolerance = 1e-11;
  int max_iterations = 40;  // Newton steps, >= 1
  // Wall-clock limit in seconds, checked after every period-map evaluation
  // (one evaluation is not interrupted); 0: none, else finite and > 0.
  double time_limit = 0.0;
  ShootingProgress progress;  // optional
  // Throws InputError naming the field.
  void validate() const;
};

struct ShootingResult {
  bool converged = false;
  std::string failure;             // why not converged
  int iterations = 0;              // Newton steps taken
  int flow_evaluations = 0;        // period-map evaluations (with or without Jacobian)
  double start_time = 0.0;         // t0 of the state below
  Eigen::VectorXd state;           // y(t0) = [x; v] on the orbit
  double period_residual = 0.0;    // ‖P(y) − y‖∞ / ‖y‖∞ at the returned state
  Eigen::MatrixXd monodromy;       // Φ at the returned state
  // Floquet multipliers: the eigenvalues of Φ, largest modulus first. Only
  // for a converged orbit (empty otherwise: Φ at a point that is not on a
  // periodic orbit has no such meaning), as are the two below.
  Eigen::VectorXcd multipliers;
  double spectral_radius = 0.0;
  bool stable = false;             // spectral radius < 1
  std::map<std::string, int> events;  // per period, by kind
  Eigen::VectorXd max_abs;         // max over the period of |x_i|
  double seconds = 0.0;            // whole shooting
  double seconds_per_orbit = 0.0;  // one period-map evaluation with Jacobian
};

ShootingResult shootPeriodicOrbit(const Flow& flow, const Eigen::VectorXd& start, double start_time,
                                  const ShootingOptions& options);

// Shooting from the harmonic-balance solution `full` ([x; λ] on the
// model's basis), started at its quiet instant (quietStartTime, below), which
// the result carries as start_time.
ShootingResult shootFromHarmonicBalance(const Flow& flow, const HbModel& model, const Eigen::VectorXd& full,
                                        const ShootingOptions& options);

// Distance from samples of another solution, displacement row i at
// t = iT/S (S = rows; a time reference's last period), to the orbit:
// max over samples and DOFs of |x − x_orbit| / max|x_orbit|. Returns NaN if
// the flow fails.
double distanceToOrbit(const Flow& flow, const ShootingResult& orbit, const Eigen::MatrixXd& displacement);

// y(t) = [x(t); ẋ(t)] of the displacement Fourier series in `full`
// ([x; λ] coefficients on the model's basis), followed by the slider
// position w = x + r/k_t of each Jenkins law on one DOF (the state of
// PiecewiseLinearFlow).
Eigen::VectorXd harmonicState(const HbModel& model, const Eigen::VectorXd& full, double t);

// The instant of the period (among N samples) where the harmonic solution
// is farthest from any event: largest min over laws of |v|/max|v| (friction)
// or gap/max gap (contact). Shooting starts there, away from kinks.
double quietStartTime(const HbModel& model, const Eigen::VectorXd& full);

}  // namespace eqhb::orbits
