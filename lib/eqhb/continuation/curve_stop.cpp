#include "eqhb/continuation/curve_stop.h"

#include <cstdio>

#include "eqhb/error.h"

namespace eqhb {

std::string CurveStop::due() const {
  if (wasRequested()) return "stopped on request (a signal)";
  if (!deadline.passed()) return "";
  char after[32];
  std::snprintf(after, sizeof after, "%.2f", deadline.elapsed());
  return "curve_time_limit of " + formatNumber(deadline.seconds()) + " s reached (after " + after + " s)";
}

}  // namespace eqhb
