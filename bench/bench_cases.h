// One benchmark case: a scene solved by one backend on one system (condensed
// or full) in one formulation, repeated for a median time, with its accuracy
// against the scene's references of truth.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_truth.h"
#include "report_number.h"

namespace eqhb::bench {

struct Case {
  std::string study, scene, solver, system, form;
  int harmonics = 0;
  bool converged = false;
  std::string termination;
  int iterations = 0, residual_evaluations = 0, jacobian_evaluations = 0, repeats = 0;
  double residual_norm = NAN, median_seconds = NAN, ratio_to_dogleg = NAN;
  double error_reference = NAN;  // relative L2 of x (worst DOF) vs the time-domain reference or exact orbit
  double error_high_h = NAN;     // the same vs the 4x-H solution
  // Where the reference is an exact orbit and the case has the scene's H:
  // the reference harmonic balance's own distance to the orbit at that H
  // (the truncation error, which widens the verdict's tolerance).
  double truncation_error = NAN;
};

double median(std::vector<double> v);

// The backend name under which a case runs the library's default path: the
// own dogleg, then the fallback chain where it fails (default_path.h).
inline constexpr const char* kDefaultPath = "default-path";

// The scene at `path` with the overrides `set`, solved from zero up to
// `repeats` times (fewer once a second is spent); accuracy against `truth`
// when it is given and the solve converged.
Case runCase(const std::string& study, const std::filesystem::path& path, const std::vector<std::string>& set,
             const std::string& solver_name, bool condensed, int repeats, double time_limit, const Truth* truth);

// Each case's median time over that of the own dogleg on the same study,
// scene, harmonics, form and system.
void setRatiosToDogleg(std::vector<Case>& cases);

// A figure in the report's tables, "-" where there is none.
inline std::string number(double x) { return reportNumber(x, 3, "-"); }

// A text field of bench.csv: quoted (RFC 4180, quotes doubled) when it holds
// a comma, a quote or a line break, so that a form such as "min, friction
// max" stays one column for the CSV readers (charts.py).
std::string csvField(const std::string& text);

// The Markdown table of one study's cases.
std::string table(const std::vector<Case>& cases, const std::string& study);

}  // namespace eqhb::bench
