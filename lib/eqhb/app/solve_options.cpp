#include "eqhb/app/solve_options.h"

#include <cmath>

#include "eqhb/error.h"

namespace eqhb::app {

namespace {
bool fail(std::string* why, const std::string& field, const std::string& value, const std::string& rule) {
  if (why) *why = field + " = " + value + ": " + rule;
  return false;
}
}  // namespace

bool SolveOptions::isValid(std::string* why) const {
  if (solver.empty()) return fail(why, "solver", "\"\"", "must name a backend (see solvers)");
  if (cold_start != "coarse" && cold_start != "zero")
    return fail(why, "cold_start", "\"" + cold_start + "\"", "must be \"coarse\" or \"zero\"");
  if (from_harmonics && *from_harmonics < 1)
    return fail(why, "from_harmonics", std::to_string(*from_harmonics), "must be >= 1");
  if (initial.size() && !initial.allFinite()) return fail(why, "initial", "(vector)", "must be finite");
  if (repeat < 1 || repeat > 100000) return fail(why, "repeat", std::to_string(repeat), "must be in [1, 100000]");
  if (stability_method != "hill" && stability_method != "monodromy" && stability_method != "auto")
    return fail(why, "stability_method", "\"" + stability_method + "\"", "must be hill, monodromy or auto");
  if (!(stability_time_limit >= 0.0) || !std::isfinite(stability_time_limit))
    return fail(why, "stability_time_limit", formatNumber(stability_time_limit), "must be finite and >= 0 (0: none)");
  if (accuracy_test != "auto" && accuracy_test != "estimate")
    return fail(why, "accuracy_test", "\"" + accuracy_test + "\"", "must be \"auto\" or \"estimate\"");
  if (!refine.empty() && refine != "shoot") return fail(why, "refine", "\"" + refine + "\"", "must be \"shoot\" or empty");
  if (refine_harmonics < 0)
    return fail(why, "refine_harmonics", std::to_string(refine_harmonics), "must be >= 0");
  if (refine.empty() && refine_harmonics)
    return fail(why, "refine_harmonics", std::to_string(refine_harmonics), "needs refine = shoot");
  return solver_options.isValid(why);
}

void validate(const SolveOptions& options) {
  std::string why;
  if (!options.isValid(&why)) throw InputError(why);
}

}  // namespace eqhb::app
