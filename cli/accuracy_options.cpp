#include "accuracy_options.h"

namespace eqhb::cli {

void addAccuracyOptions(CLI::App* cmd, AccuracyArguments& a) {
  cmd->add_flag("--error-estimate", a.error_estimate,
                "Estimate the relative error of max|x| by one more solve at 2H (costs that solve)");
  cmd->add_option("--accuracy", a.tolerance,
                  "Choose the cheapest H (doubling from --harmonics or 5, N following H) whose estimated "
                  "relative error of max|x| is <= TOL");
  cmd->add_option("--max-harmonics", a.max_harmonics, "With --accuracy: the largest H solved")->capture_default_str();
}

nlohmann::json errorEstimateJson(const ErrorEstimate& e) {
  return {{"max_abs", e.max_abs},
          {"coefficients", e.coefficients},
          {"max_abs_difference", e.max_abs_difference},
          {"factor", e.factor},
          {"method", "solve at 2H"},
          {"refined_harmonics", e.refined_harmonics},
          {"refined_samples", e.refined_samples},
          {"refined_converged", e.available}};
}

nlohmann::json accuracyJson(const AccuracyChoice& c, double tolerance) {
  nlohmann::json ladder = nlohmann::json::array();
  for (const auto& r : c.ladder) {
    nlohmann::json rung = {{"harmonics", r.harmonics}, {"samples", r.samples}, {"converged", r.converged},
                           {"seconds", r.seconds}};
    rung["estimate"] = r.estimated ? nlohmann::json(r.estimate) : nlohmann::json(nullptr);
    ladder.push_back(rung);
  }
  nlohmann::json out = {{"tolerance", tolerance}, {"reached", c.reached}, {"seconds", c.seconds}, {"ladder", ladder}};
  if (!c.reached) out["failure"] = c.failure;
  return out;
}

}  // namespace eqhb::cli
