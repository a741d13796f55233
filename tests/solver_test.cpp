#include "eqhb/solver.h"

#include <gtest/gtest.h>

#include <cmath>

#include "minpack/minpack_hybrj.h"
#include "registry.h"

namespace eqhb {
namespace {

// g(z) = z − 1 componentwise, or NaN from the `poison_after`-th residual call.
class ShiftSystem : public SquareSystem {
 public:
  explicit ShiftSystem(int poison_after = -1) : poison_after_(poison_after) {}
  int size() const override { return 3; }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override {
    g = z.array() - 1.0;
    if (poison_after_ >= 0 && calls_++ >= poison_after_) g[1] = std::nan("");
    return true;  // the NaN must be caught by the monitor, not trusted
  }
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> j) override {
    j.setIdentity();
    return residual(z, g);
  }

 private:
  int poison_after_;
  int calls_ = 0;
};

class EveryBackend : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryBackend, SolvesAnEasySystem) {
  ShiftSystem system;
  const SolverResult r = makeSolver(GetParam())->solve(system, Eigen::VectorXd::Zero(3), {});
  EXPECT_TRUE(r.converged()) << r.summary();
  EXPECT_LE(r.final_norm, 1e-10);
}

TEST_P(EveryBackend, NanResidualIsAnEvaluationFailureNotACrash) {
  for (int poison_after : {0, 1}) {
    ShiftSystem system(poison_after);
    const SolverResult r = makeSolver(GetParam())->solve(system, Eigen::VectorXd::Zero(3), {});
    EXPECT_EQ(r.termination, Termination::kEvaluationFailed) << r.summary();
    EXPECT_FALSE(r.converged());
  }
}

TEST_P(EveryBackend, InvalidOptionsAreRejectedBeforeAnyEvaluation) {
  ShiftSystem system;
  SolverOptions options;
  options.max_iterations = 0;
  SolverResult r = makeSolver(GetParam())->solve(system, Eigen::VectorXd::Zero(3), options);
  EXPECT_EQ(r.termination, Termination::kInvalidOptions);
  EXPECT_NE(r.native_message.find("max_iterations = 0"), std::string::npos) << r.native_message;
  EXPECT_EQ(r.residual_evaluations, 0);
  options = {};
  options.backend["no_such_option"] = "1";
  r = makeSolver(GetParam())->solve(system, Eigen::VectorXd::Zero(3), options);
  EXPECT_EQ(r.termination, Termination::kInvalidOptions);
}

INSTANTIATE_TEST_SUITE_P(Registered, EveryBackend, ::testing::Values("dogleg", "dogleg-newton", "minpack"));

TEST(Solver, ConvergedOnlyWithinTheTolerance) {
  // A tolerance that cannot be met on a system with no root: |g| >= 1.
  class NoRoot : public SquareSystem {
   public:
    int size() const override { return 1; }
    bool residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override {
      g[0] = z[0] * z[0] + 1.0;
      return true;
    }
    bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                             Eigen::Ref<Eigen::MatrixXd> j) override {
      j(0, 0) = 2 * z[0];
      return residual(z, g);
    }
  } system;
  for (const auto& entry : registeredSolvers()) {
    const SolverResult r = makeSolver(entry.name)->solve(system, Eigen::VectorXd::Constant(1, 3.0), {});
    EXPECT_FALSE(r.converged()) << r.summary();
    EXPECT_GE(r.final_norm, 1.0);
  }
}

TEST(Solver, MinpackStatusTable) {
  EXPECT_EQ(minpackTermination(0), Termination::kInvalidOptions);
  EXPECT_EQ(minpackTermination(1), Termination::kStepTolerance);
  EXPECT_EQ(minpackTermination(2), Termination::kEvaluationLimit);
  EXPECT_EQ(minpackTermination(3), Termination::kStepTolerance);
  EXPECT_EQ(minpackTermination(4), Termination::kNotProgressing);
  EXPECT_EQ(minpackTermination(5), Termination::kNotProgressing);
  EXPECT_EQ(minpackTermination(-1), Termination::kConverged);
  EXPECT_EQ(minpackTermination(-2), Termination::kEvaluationFailed);
  EXPECT_EQ(minpackTermination(-3), Termination::kTimeLimit);
  EXPECT_EQ(minpackTermination(42), Termination::kBackendError);
}

TEST(Solver, RegistryRejectsUnknownNames) {
  EXPECT_THROW(makeSolver("newton-raphson-deluxe"), std::invalid_argument);
  EXPECT_GE(registeredSolvers().size(), 2u);
}

}  // namespace
}  // namespace eqhb
