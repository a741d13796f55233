// The error estimate of harmonic balance (one more solve at 2H) against the
// true error measured on the exact periodic orbit: estimate ÷ true error of
// max|x| per scene and H, and the tally over every case.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb::bench {

struct EstimateTally {
  int cases = 0;           // estimate and true error both measured, true error above rounding
  int within_factor_3 = 0;
  std::vector<std::string> underestimates;  // "scene ω H: ratio" with ratio < 1/3
  std::vector<std::string> overestimates;   // ratio > 3
  std::vector<double> ratios;
};

// A Markdown table: per H, the estimated and the true relative error of
// max|x| (worst DOF) and their ratio. `exact_max_abs` is max|x_i| of the
// exact orbit; `label` names the case in the tally.
std::string errorEstimateTable(const HbModel& model, const Eigen::VectorXd& exact_max_abs,
                               const std::vector<int>& harmonics, const std::string& label, EstimateTally* tally);

// The tally as Markdown: how many within a factor 3, the ratio quantiles,
// every underestimate named.
std::string errorEstimateSummary(const EstimateTally& tally);

}  // namespace eqhb::bench
