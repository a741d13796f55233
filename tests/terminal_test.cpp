// Helper programs run without a shell, and the progress line's durations.
#include <gtest/gtest.h>

#include "terminal/progress.h"
#include "terminal/run_program.h"

namespace eqhb::cli {

TEST(RunProgram, ArgumentsReachTheProgramUnchanged) {
  // A shell would split these and run the second command.
  const auto out = programOutput({"printf", "%s|%s", "it's; touch x", "$(echo no)"});
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(*out, "it's; touch x|$(echo no)");
}

TEST(RunProgram, ExitStatusAndMissingPrograms) {
  EXPECT_EQ(runProgram({"sh", "-c", "exit 3"}), 3);
  EXPECT_EQ(runProgram({"true"}), 0);
  EXPECT_THROW(runProgram({"/nonexistent/program"}), std::runtime_error);
  EXPECT_FALSE(programOutput({"/nonexistent/program"}).has_value());
  EXPECT_FALSE(programOutput({"false"}).has_value());
}

TEST(Progress, Durations) {
  EXPECT_EQ(formatDuration(0.04), "0.0 s");
  EXPECT_EQ(formatDuration(12.34), "12.3 s");
  EXPECT_EQ(formatDuration(245.0), "4 min 05 s");
  EXPECT_EQ(formatDuration(3725.0), "1 h 02 min");
  EXPECT_EQ(formatDuration(-1.0), "?");
}

}  // namespace eqhb::cli
