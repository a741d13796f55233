#include "eqhb/solvers/solver.h"

#include <gtest/gtest.h>

#include <cmath>


#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/solvers/option_check.h"

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

TEST_P(EveryBackend, AnExceptionInTheResidualIsAnEvaluationFailure) {
  class Throwing : public ShiftSystem {
   public:
    bool residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override {
      if (++calls > 1) throw std::runtime_error("model blew up");
      return ShiftSystem::residual(z, g);
    }
    bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                             Eigen::Ref<Eigen::MatrixXd> j) override {
      j.setIdentity();
      return residual(z, g);
    }
    int calls = 0;
  } system;
  const SolverResult r = makeSolver(GetParam())->solve(system, Eigen::VectorXd::Zero(3), {});
  EXPECT_EQ(r.termination, Termination::kEvaluationFailed) << r.summary();
  EXPECT_NE(r.native_message.find("model blew up"), std::string::npos) << r.native_message;
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

// The check a sweep or a study makes before it starts: every backend takes
// its own defaults and a valid setting of its own, and refuses a name it does
// not know with its own message (a sweep then exits 2 instead of failing
// every point with invalid_options).
TEST_P(EveryBackend, OptionCheckTakesItsDefaultsAndRefusesAnUnknownName) {
  auto solver = makeSolver(GetParam());
  EXPECT_NO_THROW(checkSolverOptions(*solver, {}));
  SolverOptions options;
  options.backend["no_such_option"] = "1";
  try {
    checkSolverOptions(*solver, options);
    ADD_FAILURE() << GetParam() << " took an unknown option";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_option"), std::string::npos) << e.what();
  }
}

TEST(OptionCheck, TakesTheDoglegSettingsAndRefusesABadValueNamingIt) {
  auto solver = makeSolver("dogleg");
  SolverOptions options;
  options.backend = {{"factorisation", "lu"}, {"update", "refresh"}};
  EXPECT_NO_THROW(checkSolverOptions(*solver, options));
  options.backend = {{"factorisation", "bogus"}};
  try {
    checkSolverOptions(*solver, options);
    ADD_FAILURE() << "factorisation = bogus taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("factorisation = \"bogus\""), std::string::npos) << e.what();
  }
}

std::vector<std::string> registeredNames() {
  std::vector<std::string> names;
  for (const auto& entry : registeredSolvers()) names.push_back(entry.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Registered, EveryBackend, ::testing::ValuesIn(registeredNames()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

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





TEST(Solver, EvaluationLimitIsHonouredByEveryBackend) {
  // A slow, long problem: Rosenbrock-like valley in 2D.
  class Valley : public SquareSystem {
   public:
    int size() const override { return 2; }
    bool residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override {
      g << 1.0 - z[0], 100.0 * (z[1] - z[0] * z[0]);
      return true;
    }
    bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                             Eigen::Ref<Eigen::MatrixXd> j) override {
      j << -1.0, 0.0, -200.0 * z[0], 100.0;
      return residual(z, g);
    }
  };
  for (const auto& entry : registeredSolvers()) {
    Valley system;
    SolverOptions options;
    options.max_evaluations = 3;
    options.max_iterations = 3;
    const SolverResult r = makeSolver(entry.name)->solve(system, Eigen::Vector2d(-1.2, 1.0), options);
    // Newton-like backends may legitimately finish this nearly linear
    // system within 3 steps; all others must stop on the limit, saying so.
    if (r.converged()) {
      EXPECT_LE(r.final_norm, options.residual_tolerance);
      EXPECT_LE(r.iterations, 3) << r.summary();
    } else {
      EXPECT_TRUE(r.termination == Termination::kEvaluationLimit ||
                  r.termination == Termination::kIterationLimit)
          << r.summary();
    }
  }
}

// A residual within the tolerance is not enough: a point the system says
// violates its physics is no solution, whichever backend found it.
TEST_P(EveryBackend, AViolatedPhysicsIsNoSolution) {
  class Unphysical : public ShiftSystem {
   public:
    std::string violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& z) override {
      return z.isApprox(Eigen::VectorXd::Ones(3), 1e-6) ? "law[0] (test) dissipates nothing" : "";
    }
  };
  Unphysical system;
  const SolverResult r = makeSolver(GetParam())->solve(system, Eigen::VectorXd::Zero(3), {});
  EXPECT_FALSE(r.converged()) << r.summary();
  EXPECT_EQ(r.termination, Termination::kLawViolated) << r.summary();
  EXPECT_LE(r.final_norm, 1e-10) << "the residual itself converged";
  EXPECT_NE(r.native_message.find("law[0] (test) dissipates nothing"), std::string::npos) << r.native_message;
  EXPECT_STREQ(terminationName(r.termination), "law_violated");
}

TEST(Solver, RegistryRejectsUnknownNames) {
  EXPECT_THROW(makeSolver("newton-raphson-deluxe"), std::invalid_argument);
  EXPECT_GE(registeredSolvers().size(), 2u);
}

}  // namespace
}  // namespace eqhb
