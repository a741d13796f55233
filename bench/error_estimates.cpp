#include "error_estimates.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/backends/registry.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/laws/law_registry.h"
#include "report_number.h"

namespace eqhb::bench {

namespace {

std::string number(double x, int digits = 3) { return bench::reportNumber(x, digits); }

// Errors below this are rounding: no ratio is taken.
constexpr double kRoundingLevel = 1e-9;

}  // namespace

std::string errorEstimateTable(const HbModel& scene_model, const Eigen::VectorXd& exact_max_abs,
                               const std::vector<int>& harmonics, const std::string& label, EstimateTally* tally) {
  auto solver = makeSolver("dogleg");
  SolverOptions options;
  options.residual_tolerance = 1e-10;
  options.max_iterations = 400;
  // The dogleg solves contact on the full system (as the tables above).
  const bool condensed = suitsCondensedSystem(scene_model.laws);
  std::ostringstream md;
  md << "| H | N | converged (H, 2H) | estimate max\\|x\\| | true max\\|x\\| error | estimate ÷ true | "
        "estimate coefficients |\n|---|---|---|---|---|---|---|\n";
  for (int h : harmonics) {
    const HbModel model = withHarmonics(scene_model, h);
    Eigen::VectorXd full;
    const SolverResult r =
        solveByHarmonicContinuation(model, *solver, options, std::min(h, 5), condensed, &full);
    const ErrorEstimate e = estimateError(model, full, *solver, options, condensed);
    const double truth = worstRelativeDifference(peakDisplacements(model, full), exact_max_abs);
    const bool measured = r.converged() && e.available && truth > kRoundingLevel;
    const double ratio = e.max_abs / truth;
    md << "| " << h << " | " << model.samples << " | " << (r.converged() ? "yes" : "NO") << ", "
       << (e.available ? "yes" : "NO") << " | " << number(e.max_abs) << " | " << number(truth) << " | "
       << (measured ? number(ratio, 2) + (ratio < 1.0 / 3 ? " **under**" : ratio > 3 ? " (over)" : "")
                    : truth <= kRoundingLevel ? "(rounding)" : "–")
       << " | " << number(e.coefficients) << " |\n";
    if (!measured) continue;
    const std::string name = label + " H=" + std::to_string(h) + ": " + number(ratio, 2);
    ++tally->cases;
    tally->ratios.push_back(ratio);
    if (ratio >= 1.0 / 3 && ratio <= 3) ++tally->within_factor_3;
    else if (ratio < 1.0 / 3) tally->underestimates.push_back(name);
    else tally->overestimates.push_back(name);
  }
  return md.str();
}

std::string errorEstimateSummary(const EstimateTally& tally) {
  std::ostringstream md;
  md << "## Error estimates against the exact orbits\n\n"
     << "Estimate = " << kDifferenceFactor << " × |max|x|(H) − max|x|(2H)| / max|x| (worst DOF; the 2H solve "
     << "started from the H solution padded with zeros, N following H). True error = the same measure against "
     << "the exact orbit. Cases with a true error below " << kRoundingLevel << " (rounding) are not counted.\n\n";
  if (tally.cases == 0) return md.str() + "no case measured\n";
  std::vector<double> r = tally.ratios;
  std::sort(r.begin(), r.end());
  auto quantile = [&](double q) { return r[std::min(r.size() - 1, static_cast<size_t>(q * r.size()))]; };
  md << "within a factor 3: " << tally.within_factor_3 << " of " << tally.cases << " ("
     << number(100.0 * tally.within_factor_3 / tally.cases, 3) << " %); estimate ÷ true: min " << number(r.front(), 2)
     << ", median " << number(quantile(0.5), 2) << ", max " << number(r.back(), 2) << "\n\n";
  md << "underestimates (ratio < 1/3): " << (tally.underestimates.empty() ? "none" : "") << "\n";
  for (const auto& u : tally.underestimates) md << "- " << u << "\n";
  md << "\noverestimates (ratio > 3): " << (tally.overestimates.empty() ? "none" : "") << "\n";
  for (const auto& o : tally.overestimates) md << "- " << o << "\n";
  return md.str() + "\n";
}

}  // namespace eqhb::bench
