#include "eqhb/stability/multiplier_stability.h"

#include <algorithm>
#include <cmath>
#include <vector>

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
  // Largest |μ| first: the moduli are taken once, then the order.
  std::vector<double> modulus(static_cast<size_t>(multipliers.size()));
  std::vector<Eigen::Index> order(modulus.size());
  for (Eigen::Index j = 0; j < multipliers.size(); ++j) {
    modulus[j] = std::abs(multipliers[j]);
    order[j] = j;
  }
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index x, Eigen::Index y) { return modulus[x] > modulus[y]; });
  result.exponents.reserve(order.size());
  for (Eigen::Index j : order) {
    FloquetExponent e;
    e.multiplier = multipliers[j];
    e.exponent = std::complex<double>(std::log(std::max(modulus[j], 1e-300)), std::arg(e.multiplier)) / period;
    result.exponents.push_back(e);
  }
  result.spectral_radius = modulus[order.front()];
  result.stable = result.spectral_radius < 1.0 + unit_tolerance;
  return result;
}

}  // namespace eqhb
