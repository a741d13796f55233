// Every hybrj info code maps to one common termination.
#include <gtest/gtest.h>

#include "eqhb/backends/minpack/minpack_hybrj.h"

namespace eqhb {
namespace {

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

}  // namespace
}  // namespace eqhb
