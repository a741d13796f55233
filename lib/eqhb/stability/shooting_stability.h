// Stability of a harmonic-balance solution by the exact Floquet multipliers
// of the periodic orbit next to it: shooting (orbits/shooting.h) started
// from the solution at its quiet instant, on the model's exact event-driven
// flow (orbits::makeFlow: grounded Coulomb 1D, one-DOF Jenkins, Signorini
// with elastic impacts, penalty walls in closed form; cubic, polynomial,
// quadratic damping, Coulomb 2D and Stribeck by smooth phases). The
// multipliers are the eigenvalues of the period map's Jacobian with the
// saltation matrices at every event, at the exact orbit: they do not depend
// on H, whereas Hill's and the monodromy over the harmonic-balance samples
// carry the series' truncation error (on friction-1d's stick–slip orbits at
// H = 20 the monodromy's radius is 0.009-0.018 off).
//
// Shooting answers for the harmonic-balance solution only when the orbit it
// converges to is that solution's: Newton does not care which periodic
// orbit it reaches, and from a poor start (a low H, a point near a fold) it
// may reach the other branch or another stick pattern. The check: the
// largest displacement difference between the orbit and the series at the
// N samples, relative to the orbit's largest |x| (orbits::distanceToOrbit),
// is at most kSameOrbitDistance = 0.1. The truncation error of a converged
// harmonic balance is well below that (a displacement series converges as
// the orbit's first discontinuous derivative allows), while coexisting
// orbits of one forcing differ by the separation of their branches. Near a
// fold the two branches close in and no distance tells them apart; there
// Newton's start, the series, is the nearer one.
//
// When shooting fails (no convergence within the options' iterations, a
// flow failure) or lands farther than that, the point is answered by the
// monodromy (monodromy_stability.h) where its laws allow, else by Hill's
// method, and the result's `note` says why (HillResult::method names who
// answered).
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/orbits/shooting.h"
#include "eqhb/stability/hill_stability.h"

namespace eqhb {

class MonodromyStability;

class ShootingStability {
 public:
  // Largest relative displacement distance of the shot orbit from the
  // harmonic-balance series for the orbit to count as the series' (header).
  static constexpr double kSameOrbitDistance = 0.1;
  // Structures of more DOFs are not shot: the exact flow's dense
  // exponentials of the whole state cost minutes a point on beam-damper's
  // 120 DOFs (no point of its curve finished in 300 s); they are answered as
  // shooting's fallback answers (the monodromy, else Hill), with a note. The
  // same bound as the accuracy ladder's exact-orbit test.
  static constexpr int kMaxDofs = 12;

  // Throws InputError if the model or options are invalid, or the laws have
  // no exact flow (supports()).
  explicit ShootingStability(const HbModel& model, const HillOptions& options = {},
                             const orbits::ShootingOptions& shooting = defaultShooting());
  ~ShootingStability();
  ShootingStability(const ShootingStability&) = delete;
  ShootingStability& operator=(const ShootingStability&) = delete;
  // True when every law has an exact flow and is grounded.
  static bool supports(const HbModel& model);
  // Throws InputError if ω is not finite and > 0 or `full` has the wrong size.
  HillResult analyse(double omega, const Eigen::VectorXd& full);
  // The last analysis's shooting (converged or not), for measurements.
  const orbits::ShootingResult& lastShooting() const { return last_; }
  // Its distance to the series (NaN when shooting did not converge).
  double lastDistance() const { return last_distance_; }

  // Period residual 1e-10, 20 Newton steps and 2 s a point: the
  // multipliers converge with the orbit, and a start that needs more steps
  // is one that is not close to an orbit anyway (from the series it takes
  // 2-3 on the scenes measured).
  static orbits::ShootingOptions defaultShooting();

 private:
  HillResult fallback(double omega, const Eigen::VectorXd& full, const std::string& why);

  HbModel model_;
  HillOptions options_;
  orbits::ShootingOptions shooting_;
  Eigen::MatrixXd displacement_;  // N x n: the series' x at t = kT/N
  orbits::ShootingResult last_;
  double last_distance_ = 0.0;
  std::unique_ptr<MonodromyStability> monodromy_;  // made at the first fallback
  std::unique_ptr<HillStability> hill_;            // likewise, where the monodromy does not apply
};

}  // namespace eqhb
