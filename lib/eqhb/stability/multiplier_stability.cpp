#include "eqhb/stability/multiplier_stability.h"

#include <algorithm>
#include <cmath>

namespace eqhb {

HillResult stabilityFromMultipliers(const Eigen::VectorXcd& multipliers, double period, double unit_tolerance,
                                    const std::string& method) {
  HillResult result;
  result.method = method;
  result.state_dimension = result.candidates = result.pencil_size = static_cast<int>(multipliers.size());
  if (multipliers.size() == 0) {
    result.failure = "no multipliers";
    return result;
  }
  for (Eigen::Index j = 0; j < multipliers.size(); ++j) {
    FloquetExponent e;
    e.multiplier = multipliers[j];
    const double modulus = std::max(std::abs(e.multiplier), 1e-300);
    e.exponent = std::complex<double>(std::log(modulus), std::arg(e.multiplier)) / period;
    result.exponents.push_back(e);
  }
  std::stable_sort(result.exponents.begin(), result.exponents.end(),
                   [](const auto& x, const auto& y) { return std::abs(x.multiplier) > std::abs(y.multiplier); });
  result.spectral_radius = std::abs(result.exponents.front().multiplier);
  result.stable = result.spectral_radius < 1.0 + unit_tolerance;
  return result;
}

}  // namespace eqhb
