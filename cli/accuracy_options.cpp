#include "accuracy_options.h"

namespace eqhb::cli {

void addAccuracyTestOption(CLI::App* cmd, AccuracyArguments& a) {
  cmd->add_option("--accuracy-test", a.test,
                  "With --accuracy, the test of each H: auto (the exact orbit where every law has an exact flow "
                  "and the structure has at most 12 DOFs, else the estimate times its safety factor) or estimate")
      ->capture_default_str();
}

void addAccuracyOptions(CLI::App* cmd, AccuracyArguments& a) {
  cmd->add_flag("--error-estimate", a.error_estimate,
                "Estimate the relative error of max|x| by one more solve at 2H (costs that solve)");
  cmd->add_option("--accuracy", a.tolerance,
                  "Choose the cheapest H (doubling from --harmonics or 5, N following H) and, unless --rho is "
                  "given, rho (each law's times 1, 0.1 or 0.01) whose relative error of max|x| is <= TOL: against "
                  "the exact orbit (shooting) where every law has one, else by the estimate times a safety factor");
  addAccuracyTestOption(cmd, a);
  cmd->add_option("--max-harmonics", a.max_harmonics, "With --accuracy: the largest H solved")->capture_default_str();
}

}  // namespace eqhb::cli
