// Where a switching instant falls between two samples of the orbit.
#pragma once

#include <algorithm>
#include <cmath>

namespace eqhb {

// The fraction in [0, 1] of a sample interval where the linear interpolant
// of a quantity going from a to b vanishes (0.5 when it does not change).
inline double switchCrossing(double a, double b) {
  const double d = a - b;
  if (d == 0.0 || !std::isfinite(a / d)) return 0.5;
  return std::clamp(a / d, 0.0, 1.0);
}

}  // namespace eqhb
