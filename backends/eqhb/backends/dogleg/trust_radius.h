#pragma once
// The trust-region radius rule of MINPACK's hybrj, shared by the dense (Broyden) and the
// sparse (Newton) dogleg: halve after a poor step, grow to twice the step after good ones.
#include <algorithm>
#include <cmath>

namespace eqhb::dogleg {

// ratio: actual / predicted reduction of the step; step_norm: its scaled length.
inline void updateTrustRadius(double ratio, double step_norm, double& radius,
                              int& consecutive_successes) {
  if (ratio < 0.1) {
    consecutive_successes = 0;
    radius *= 0.5;
    return;
  }
  ++consecutive_successes;
  if (ratio >= 0.5 || consecutive_successes > 1) radius = std::max(radius, step_norm / 0.5);
  if (std::abs(ratio - 1.0) <= 0.1) radius = step_norm / 0.5;
}

}  // namespace eqhb::dogleg
