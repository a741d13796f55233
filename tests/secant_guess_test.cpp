#include "eqhb/continuation/secant_guess.h"

#include <gtest/gtest.h>

#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "test_support.h"

namespace eqhb {
namespace {

// g(z) = z − s(ω): a system whose solution s(ω) the test sets.
class ShiftSystem : public SquareSystem {
 public:
  explicit ShiftSystem(Eigen::VectorXd solution) : solution_(std::move(solution)) {}
  int size() const override { return static_cast<int>(solution_.size()); }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override {
    g = z - solution_;
    return true;
  }
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override {
    jacobian.setIdentity();
    return residual(z, g);
  }
  Eigen::VectorXd solution_;
};

TEST(SecantGuess, WithFewerThanTwoPointsTheGuessIsTheLastSolution) {
  const Eigen::Vector2d a(1.0, -2.0);
  ShiftSystem system(3.0 * a);
  SecantGuess guess;
  int evaluations = 0;
  EXPECT_EQ(guess.at(3.0, system, a, &evaluations), a);
  guess.accept(1.0, a);
  EXPECT_EQ(guess.at(3.0, system, a, &evaluations), a);
  EXPECT_EQ(evaluations, 0);
}

TEST(SecantGuess, TheLineThroughTheLastTwoPointsLandsOnALinearBranch) {
  const Eigen::Vector2d a(1.0, -2.0);
  ShiftSystem system(3.0 * a);  // s(ω) = ω a, at ω = 3
  SecantGuess guess;
  guess.accept(1.0, a);
  guess.accept(2.0, 2.0 * a);
  int evaluations = 0;
  const Eigen::VectorXd z = guess.at(3.0, system, 2.0 * a, &evaluations);
  EXPECT_LT((z - 3.0 * a).norm(), 1e-15);
  EXPECT_EQ(evaluations, 2);
  // Unequal steps: the line is extended by the ω moved, not by one step.
  guess.accept(3.0, 3.0 * a);
  system.solution_ = 3.5 * a;
  EXPECT_LT((guess.at(3.5, system, 3.0 * a, &evaluations) - 3.5 * a).norm(), 1e-15);
}

TEST(SecantGuess, ALineThatOvershootsIsNotTaken) {
  const Eigen::Vector2d a(1.0, -2.0);
  ShiftSystem system(2.0 * a);  // the branch stops growing at ω = 2 (a stick-slip transition)
  SecantGuess guess;
  guess.accept(1.0, a);
  guess.accept(2.0, 2.0 * a);
  int evaluations = 0;
  EXPECT_EQ(guess.at(3.0, system, 2.0 * a, &evaluations), 2.0 * a);
  // reset() forgets both points.
  guess.reset();
  EXPECT_EQ(guess.at(3.0, system, a, &evaluations), a);
}

// A sequential sweep starts each point from the secant guess: on a
// frictional beam, fewer iterations in all than solving each grid point from
// the solution before it.
TEST(SecantGuess, SequentialSweepNeedsFewerIterationsThanFromThePreviousPoint) {
  const Scene scene = loadScene(test::problem("beam-damper.toml"));
  auto solver = makeSolver("dogleg");
  ContinuationOptions options;
  options.from = *scene.sweep_from;
  options.to = *scene.sweep_to;
  options.step = 0.02;
  const Curve curve = sweepSequential(scene.model, *solver, {}, options);
  ASSERT_TRUE(curve.complete) << curve.stop_reason;
  // From the third point on, where two points are known.
  int sweep_iterations = 0, previous_point_iterations = 0;
  HbModel model = scene.model;
  auto system = makeHbSystem(model, true);
  for (size_t i = 2; i < curve.points.size(); ++i) {
    sweep_iterations += curve.points[i].iterations;
    system->setOmega(curve.points[i].omega);
    const SolverResult r = solver->solve(*system, system->fromFullCoefficients(curve.points[i - 1].full), {});
    previous_point_iterations += r.iterations;
  }
  EXPECT_LT(sweep_iterations, 0.8 * previous_point_iterations)
      << "sweep " << sweep_iterations << ", from the previous point " << previous_point_iterations;
}

}  // namespace
}  // namespace eqhb
