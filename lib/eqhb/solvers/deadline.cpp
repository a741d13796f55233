#include "eqhb/solvers/deadline.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "eqhb/error.h"

namespace eqhb {

Deadline::Deadline(double seconds) : seconds_(seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds))
    throwInputError("time limit", formatNumber(seconds), "must be finite and >= 0 (0: none)");
}

double Deadline::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double Deadline::remaining() const {
  return limited() ? seconds_ - elapsed() : std::numeric_limits<double>::infinity();
}

void Deadline::check(const std::string& where) const {
  if (!passed()) return;
  char after[32];
  std::snprintf(after, sizeof after, "%.2f", elapsed());
  throw TimeLimitReached("time limit of " + formatNumber(seconds_) + " s reached during " + where + " (after " +
                         after + " s)");
}

}  // namespace eqhb
