// The accuracy target checked against the exact orbits: `solve --accuracy
// TOL` (app::solve) on scenes whose laws all have an exact flow, at several
// ω and friction or forcing levels per scene, each answer's true error of
// max|x| measured on the exact periodic orbit shot from it. Tallies how
// often the target's claim holds: reached, true error <= TOL and <= 1.5 TOL
// among the reached cases, the worst true error ÷ TOL, and the time.
#pragma once

#include <string>
#include <vector>

#include "eqhb/accuracy/rung_test.h"

namespace eqhb::bench {

struct TallyCase {
  std::string file;                    // in problems/
  double omega = 0.0;
  std::vector<std::string> overrides;  // "law[0].muN=4", ...
  std::string label;                   // what the overrides change, for the table
};

// The cases: friction-1d, Coulomb oscillator, friction-2d (stick-slip and
// sliding), Stribeck, jenkins-1d and contact (e = 1), 46 in all.
std::vector<TallyCase> accuracyTallyCases();

struct TallyOptions {
  double tolerance = 1e-3;
  int max_harmonics = 320;
  std::string accuracy_test = "auto";  // app::SolutionChecks::accuracy_test
  double safety_factor = kEstimateSafetyFactor;  // of the estimate (AccuracyTestOptions)
  std::string only;                    // only the cases whose file name contains this
};

// Runs every case and returns the Markdown table and its tally.
std::string accuracyTally(const std::vector<TallyCase>& cases, const TallyOptions& options);

}  // namespace eqhb::bench
