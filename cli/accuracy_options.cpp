#include "accuracy_options.h"

namespace eqhb::cli {

void addAccuracyOptions(CLI::App* cmd, AccuracyArguments& a) {
  cmd->add_flag("--error-estimate", a.error_estimate,
                "Estimate the relative error of max|x| by one more solve at 2H (costs that solve)");
  cmd->add_option("--accuracy", a.tolerance,
                  "Choose the cheapest H (doubling from --harmonics or 5, N following H) and, unless --rho is "
                  "given, rho (each law's times 1, 0.1 or 0.01) whose estimated relative error of max|x| is <= TOL");
  cmd->add_option("--max-harmonics", a.max_harmonics, "With --accuracy: the largest H solved")->capture_default_str();
}

}  // namespace eqhb::cli
