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
// displacements over one period (worst DOF) against the reference (a
// time-domain run, or a Signorini wall's exact orbit with elastic impacts)
// or the 4x-H solution, at most this. Correct answers on the shipped scenes
// are within 0.065 of their time references at the scenes' own H
// (truncation error) and contact's within 0.103 of its exact orbit; the
// spurious roots found on the damper are off by 37 to 79. (Against the
// plastic-impact time run contact was 0.25 off: another orbit.)
inline constexpr double kAgreementTolerance = 0.1;

// Where the method itself is further than kAgreementTolerance from the
// exact orbit at the case's H (its truncation error there: the reference
// harmonic balance at that H against the orbit), no solver can meet that
// tolerance; the case is then judged against this multiple of the
// truncation error instead. Not one harmonic balance: at the same H the
// forms and ρ project Ψ differently and their answers differ (contact at
// H = 20: min 0.0014, sign-square 0.014 from Fischer–Burmeister's), each as
// far from the orbit as the method is (0.088 to 0.103), while a spurious
// root or another branch is off by order one.
inline constexpr double kTruncationFactor = 2.0;

// The agreement asked of a case with the given truncation error (NaN: none known).
double agreementTolerance(double truncation_error);

enum class Verdict {
  kSolved,       // converged and within agreementTolerance(truncation) of a reference
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
