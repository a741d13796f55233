#include "eqhb/harmonic_balance/force_resolution.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_solution.h"

namespace eqhb {

namespace {

double rootMeanSquare(const std::vector<double>& a, size_t from, size_t to) {
  double sum = 0.0;
  for (size_t i = from; i < to; ++i) sum += a[i] * a[i];
  return std::sqrt(sum / static_cast<double>(to - from));
}

}  // namespace

std::optional<UnresolvedForce> worstUnresolvedForce(const HbModel& model, const Eigen::VectorXd& full) {
  const HarmonicSet& basis = model.basis;
  const int nb = basis.size(), dofs = model.structure.dofs();
  if (full.size() != static_cast<Eigen::Index>(dofs + model.lawComponents()) * nb) return std::nullopt;
  // Amplitudes |(a_k, b_k)| of the non-constant harmonics, in order.
  std::vector<int> ks;
  std::vector<int> offsets;
  for (size_t h = 0; h < basis.harmonics().size(); ++h)
    if (basis.harmonics()[h] > 0) {
      ks.push_back(basis.harmonics()[h]);
      offsets.push_back(basis.offset(static_cast<int>(h)));
    }
  const size_t n = ks.size();
  if (n < static_cast<size_t>(kFewestHarmonicsForResolution)) return std::nullopt;
  const size_t middle_from = n / 4, middle_to = n / 2, top_from = 3 * n / 4;
  std::optional<UnresolvedForce> worst;
  std::vector<double> amplitude(n);
  for (size_t l = 0; l < model.laws.size(); ++l)
    for (int a = 0; a < model.laws[l].law->dimension(); ++a) {
      const double* c = full.data() + static_cast<Eigen::Index>(dofs + model.componentIndex(static_cast<int>(l), a)) * nb;
      for (size_t i = 0; i < n; ++i) amplitude[i] = std::hypot(c[offsets[i]], c[offsets[i] + 1]);
      const double largest = *std::max_element(amplitude.begin(), amplitude.end());
      const double top = rootMeanSquare(amplitude, top_from, n), middle = rootMeanSquare(amplitude, middle_from, middle_to);
      if (!(largest > 0.0) || !std::isfinite(top) || top < kNegligibleTop * largest || !(top > middle)) continue;
      const double rise = middle > 0.0 ? top / middle : INFINITY;
      if (worst && !(rise > worst->rise)) continue;
      worst = UnresolvedForce{static_cast<int>(l), a, rise, ks[top_from], ks[n - 1], ks[middle_from], ks[middle_to - 1]};
    }
  return worst;
}

std::string unresolvedForceNote(const HbModel& model, const Eigen::VectorXd& full) {
  const auto worst = worstUnresolvedForce(model, full);
  if (!worst) return "";
  const std::string rise = std::isfinite(worst->rise) ? formatNumber(std::round(worst->rise * 10.0) / 10.0) + " times" : "above";
  return "law " + std::to_string(worst->law + 1) + "'s force (" + lawComponentLabel(model, worst->law, worst->component) +
         ") is not resolved at H = " + std::to_string(model.basis.count()) + " near omega = " + formatNumber(model.omega) +
         ": its harmonics " + std::to_string(worst->top_from) + "-" + std::to_string(worst->top_to) + " are " + rise +
         " its harmonics " + std::to_string(worst->middle_from) + "-" + std::to_string(worst->middle_to) +
         " (a spectrum rising toward the truncation: events the harmonics cannot follow, where the branches of harmonic "
         "balance break up); fewer harmonics, or a compliant law, may get through";
}

}  // namespace eqhb
