// The starting point of a sequential sweep's next grid point: the last
// solution, or the line through the last two extended to the new ω (a secant
// predictor), whichever has the smaller scaled residual there. Near a
// stick-slip transition the line can overshoot, so it is checked rather than
// trusted: the guess never starts further from a solution, in the residual the
// solver judges, than the last solution would.
#pragma once

#include <Eigen/Dense>

#include "eqhb/solvers/square_system.h"

namespace eqhb {

class SecantGuess {
 public:
  // Forgets the points: the next guess is the last solution as given.
  void reset() { have_last_ = have_previous_ = false; }
  // A converged point at ω.
  void accept(double omega, const Eigen::VectorXd& z);
  // The guess at `omega` (the system already set there), or `fallback` when
  // fewer than two points are known. `evaluations` counts the residuals
  // evaluated to choose.
  Eigen::VectorXd at(double omega, SquareSystem& system, const Eigen::VectorXd& fallback, int* evaluations);

 private:
  double scaledNorm(SquareSystem& system, const Eigen::VectorXd& z, int* evaluations);
  bool have_last_ = false, have_previous_ = false;
  double last_omega_ = 0.0, previous_omega_ = 0.0;
  Eigen::VectorXd last_, previous_, residual_, scales_;
};

}  // namespace eqhb
