// Every Ceres termination type maps to one common termination.
#include <gtest/gtest.h>

#include <ceres/types.h>

#include "eqhb/backends/ceres/ceres_backend.h"

namespace eqhb {
namespace {

TEST(Solver, CeresStatusTable) {
  EXPECT_EQ(ceresTermination(ceres::CONVERGENCE), Termination::kStepTolerance);
  EXPECT_EQ(ceresTermination(ceres::NO_CONVERGENCE), Termination::kIterationLimit);
  EXPECT_EQ(ceresTermination(ceres::FAILURE), Termination::kEvaluationFailed);
  EXPECT_EQ(ceresTermination(ceres::USER_SUCCESS), Termination::kConverged);
  EXPECT_EQ(ceresTermination(ceres::USER_FAILURE), Termination::kBackendError);
}

}  // namespace
}  // namespace eqhb
