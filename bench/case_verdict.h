// Whether a benchmark case solved its problem: a backend that reports
// convergence has only met its residual tolerance; the answer may still be a
// spurious root of the truncated equations or another solution branch than
// the one the references follow. A case counts as solved only if its answer
// also agrees with one of the scene's references of truth.
#pragma once

#include <string>
#include <vector>

#include "bench_cases.h"

namespace eqhb::bench {

// The agreement asked of a converged answer: relative L2 error of the
// displacements over one period (worst DOF) against the time-domain
// reference or the 4x-H solution, at most this. Correct answers on the
// shipped scenes are within 0.065 of their references at the scenes' own H
// (truncation error); the spurious roots found on the damper are off by 37
// to 79. Between the two lie answers too coarse for their law (contact at
// H = 20: 0.25 from its reference, with no 4x-H solution to judge by).
inline constexpr double kAgreementTolerance = 0.1;

enum class Verdict {
  kSolved,       // converged and within kAgreementTolerance of a reference
  kDisagrees,    // converged, but agrees with neither reference
  kUnchecked,    // converged, and the scene has no reference to check it against
  kFailed,       // did not converge
};

Verdict verdictOf(const Case& c);
// "solved", "disagrees", "unchecked", "failed" (bench.json, bench.csv).
const char* verdictName(Verdict verdict);
// The rule above in one sentence, for the report.
std::string verdictRule();

// The backend to use by default and the one to fall back on, from the scene
// study: the default solves the most cases (ties: the lowest geometric mean
// time over the cases it solves); the fallback solves the most of the cases
// the default does not.
struct DefaultChoice {
  std::string default_backend, fallback_backend;
  int cases = 0;              // scene-study cases with a reference
  int default_solved = 0;     // of those
  int either_solved = 0;      // by the default or the fallback
  int default_disagreements = 0;
};
DefaultChoice chooseDefault(const std::vector<Case>& cases);

}  // namespace eqhb::bench
