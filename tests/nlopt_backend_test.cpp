// Every nlopt_result maps to one common termination.
#include <gtest/gtest.h>

#include <nlopt.h>

#include "eqhb/backends/nlopt/nlopt_backend.h"

namespace eqhb {
namespace {

TEST(Solver, NloptStatusTable) {
  EXPECT_EQ(nloptTermination(NLOPT_SUCCESS), Termination::kConverged);
  EXPECT_EQ(nloptTermination(NLOPT_STOPVAL_REACHED), Termination::kConverged);
  EXPECT_EQ(nloptTermination(NLOPT_FTOL_REACHED), Termination::kStepTolerance);
  EXPECT_EQ(nloptTermination(NLOPT_XTOL_REACHED), Termination::kStepTolerance);
  EXPECT_EQ(nloptTermination(NLOPT_MAXEVAL_REACHED), Termination::kEvaluationLimit);
  EXPECT_EQ(nloptTermination(NLOPT_MAXTIME_REACHED), Termination::kTimeLimit);
  EXPECT_EQ(nloptTermination(NLOPT_ROUNDOFF_LIMITED), Termination::kNotProgressing);
  EXPECT_EQ(nloptTermination(NLOPT_INVALID_ARGS), Termination::kInvalidOptions);
  EXPECT_EQ(nloptTermination(NLOPT_FAILURE), Termination::kBackendError);
}

}  // namespace
}  // namespace eqhb
