#include "eqhb/app/solver_choice.h"

#include <cmath>

#include "eqhb/error.h"

namespace eqhb::app {

bool SolutionChecks::isValid(std::string* why) const {
  if (stability_method != "hill" && stability_method != "monodromy" && stability_method != "shooting" &&
      stability_method != "auto")
    return refuseOption(why, "stability_method", "\"" + stability_method + "\"",
                        "must be hill, monodromy, shooting or auto");
  if (!(stability_time_limit >= 0.0) || !std::isfinite(stability_time_limit))
    return refuseOption(why, "stability_time_limit", formatNumber(stability_time_limit),
                        "must be finite and >= 0 (0: none)");
  if (accuracy_test != "auto" && accuracy_test != "estimate")
    return refuseOption(why, "accuracy_test", "\"" + accuracy_test + "\"", "must be \"auto\" or \"estimate\"");
  return true;
}

}  // namespace eqhb::app
