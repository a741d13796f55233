// The scaled trust-region loop shared by the dense and the sparse dogleg, in
// the class of MINPACK's hybrj (Moré, Garbow, Hillstrom, "User guide for
// MINPACK-1", ANL-80-74, 1980): a fresh Jacobian sets the column scaling D
// (and, until a step succeeds, the radius); steps are taken on its model by
// a DoglegStrategy and judged by the actual/predicted reduction ratio of
// ‖g‖²; the radius follows trust_radius.h; seven named stopping tests.
#pragma once

#include <Eigen/Dense>

#include "eqhb/backends/dogleg/dogleg_strategy.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

struct DoglegSettings {
  double factor = 100.0;  // initial trust radius = factor · ‖D z0‖
  double xtol = 1e-14;    // stop when radius <= xtol · ‖D z‖
  bool scale_columns = true;
  // The dense model's factorisation: QR (hybrj's Q R, updated by rotations)
  // or LU (dense_lu_strategy.h); auto: LU from kDenseLuFromUnknowns.
  enum class Factorisation { kAuto, kQr, kLu } factorisation = Factorisation::kAuto;
  // Between LUs of the dense LU strategy with the Broyden policy: the
  // Jacobian at each accepted iterate, solved by GMRES on the LU kept
  // (kRefresh), or Broyden's secant updates (kBroyden).
  enum class Update { kRefresh, kBroyden } update = Update::kRefresh;
};

namespace dogleg {

// Runs the loop from z0 with `strategy`'s models; fills result as
// Solver::run does.
void runTrustRegionLoop(MonitoredSystem& system, const Eigen::VectorXd& z0, const SolverOptions& options,
                        const DoglegSettings& settings, DoglegStrategy& strategy, SolverResult& result);

}  // namespace dogleg
}  // namespace eqhb
