#include "eqhb/app/solve_options.h"

#include <cmath>

#include "eqhb/error.h"

namespace eqhb::app {

bool SolveOptions::isValid(std::string* why) const {
  if (solver.empty()) return refuseOption(why, "solver", "\"\"", "must name a backend (see solvers)");
  if (cold_start != "coarse" && cold_start != "zero")
    return refuseOption(why, "cold_start", "\"" + cold_start + "\"", "must be \"coarse\" or \"zero\"");
  if (from_harmonics && *from_harmonics < 1)
    return refuseOption(why, "from_harmonics", std::to_string(*from_harmonics), "must be >= 1");
  if (initial.size() && !initial.allFinite()) return refuseOption(why, "initial", "(vector)", "must be finite");
  if (repeat < 1 || repeat > 100000)
    return refuseOption(why, "repeat", std::to_string(repeat), "must be in [1, 100000]");
  if (!SolutionChecks::isValid(why)) return false;
  if (!refine.empty() && refine != "shoot")
    return refuseOption(why, "refine", "\"" + refine + "\"", "must be \"shoot\" or empty");
  if (refine_harmonics < 0)
    return refuseOption(why, "refine_harmonics", std::to_string(refine_harmonics), "must be >= 0");
  if (refine.empty() && refine_harmonics)
    return refuseOption(why, "refine_harmonics", std::to_string(refine_harmonics), "needs refine = shoot");
  return solver_options.isValid(why);
}

void validate(const SolveOptions& options) {
  std::string why;
  if (!options.isValid(&why)) throw InputError(why);
}

}  // namespace eqhb::app
