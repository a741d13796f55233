// Every Ipopt SolverReturn maps to one common termination.
#include <gtest/gtest.h>

#include <IpAlgTypes.hpp>

#include "eqhb/backends/ipopt/ipopt_backend.h"

namespace eqhb {
namespace {

TEST(Solver, IpoptStatusTable) {
  EXPECT_EQ(ipoptTermination(Ipopt::SUCCESS), Termination::kConverged);
  EXPECT_EQ(ipoptTermination(Ipopt::STOP_AT_ACCEPTABLE_POINT), Termination::kConverged);
  EXPECT_EQ(ipoptTermination(Ipopt::FEASIBLE_POINT_FOUND), Termination::kConverged);
  EXPECT_EQ(ipoptTermination(Ipopt::MAXITER_EXCEEDED), Termination::kIterationLimit);
  EXPECT_EQ(ipoptTermination(Ipopt::CPUTIME_EXCEEDED), Termination::kTimeLimit);
  EXPECT_EQ(ipoptTermination(Ipopt::STOP_AT_TINY_STEP), Termination::kStepTolerance);
  EXPECT_EQ(ipoptTermination(Ipopt::LOCAL_INFEASIBILITY), Termination::kNotProgressing);
  EXPECT_EQ(ipoptTermination(Ipopt::DIVERGING_ITERATES), Termination::kNotProgressing);
  EXPECT_EQ(ipoptTermination(Ipopt::RESTORATION_FAILURE), Termination::kNotProgressing);
  EXPECT_EQ(ipoptTermination(Ipopt::INVALID_NUMBER_DETECTED), Termination::kEvaluationFailed);
  EXPECT_EQ(ipoptTermination(Ipopt::TOO_FEW_DEGREES_OF_FREEDOM), Termination::kInvalidOptions);
  EXPECT_EQ(ipoptTermination(Ipopt::INVALID_OPTION), Termination::kInvalidOptions);
  EXPECT_EQ(ipoptTermination(Ipopt::ERROR_IN_STEP_COMPUTATION), Termination::kBackendError);
  EXPECT_EQ(ipoptTermination(Ipopt::INTERNAL_ERROR), Termination::kBackendError);
}

}  // namespace
}  // namespace eqhb
