// A posteriori error estimate of one harmonic-balance solution, by one more
// solve on twice the harmonics.
//
// Why this estimator: the harmonic-balance error of the nonsmooth laws falls
// only algebraically, e ∝ H^-p with p measured between 0.85 and 1.45 against
// the exact periodic orbits (spectrally for smooth laws). If e(2H) = 2^-p e(H)
// with errors of one sign, the difference d = |m(H) − m(2H)| of a quantity m
// is (1 − 2^-p) e(H), so e(H) = d / (1 − 2^-p): 2.25 d at p = 0.85, 1.58 d at
// p = 1.45, d for a spectral rate. The estimate is kDifferenceFactor d with
// the factor 2 of p = 1, within a factor 1.5 of all three. The defect of the
// exact law along the HB trajectory was not chosen: for set-valued laws it is
// not a distance in x (a sticking phase has no defect in r ∈ [−μN, μN] but
// the error of its end instant moves the whole orbit).
#pragma once

#include <Eigen/Dense>

#include <string>

#include "eqhb/continuation/fallback_chain.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

// e(H) ≈ kDifferenceFactor · |m(H) − m(2H)| (rate p = 1, see above).
constexpr double kDifferenceFactor = 2.0;

// A DOF at rest (held by friction, or not excited) is measured against this
// fraction of the largest max|x| of the solution, not against its own.
constexpr double kRestFloor = 1e-3;

// The same scene on `harmonics` harmonics of the same kind, N following H:
// N scaled by the ratio of the highest harmonics (rounded up to an even
// number) and at least 2 k_max + 1.
HbModel withHarmonics(const HbModel& model, int harmonics);

// max_t |x_i(t)| per DOF of the truncated series (coefficients in the
// FullSystem layout): sampled at 16 points per period of k_max, then the best
// sample refined by golden-section search (the samples alone are ~1e-6
// relative off at a peak, which is the size of the errors measured here).
Eigen::VectorXd peakDisplacements(const HbModel& model, const Eigen::VectorXd& full);

// Worst relative difference per DOF, each DOF against max(|reference_i|,
// kRestFloor · max_j |reference_j|).
double worstRelativeDifference(const Eigen::VectorXd& value, const Eigen::VectorXd& reference);

struct ErrorEstimate {
  bool available = false;       // the refined solve converged
  double max_abs = 0.0;         // estimated relative error of max|x|, worst DOF
  double coefficients = 0.0;    // estimated relative error of the displacement coefficients (2-norm)
  double max_abs_difference = 0.0;  // |max|x|(H) − max|x|(2H)|, relative, worst DOF
  double factor = kDifferenceFactor;
  int refined_harmonics = 0;
  int refined_samples = 0;
  SolverResult refined;         // the solve at 2H
  std::string fallback;         // the fallback step that converged it (empty: none needed or none did)
  Eigen::VectorXd refined_full; // its coefficients, FullSystem layout on withHarmonics(model, 2H)
};

// Solves `model` at 2H from `full` (its solution at H, padded with zero
// harmonics) with `solver` on the condensed or full system, and compares.
// If the refined solve does not converge, `fallbacks`' steps are tried
// (none when it is null or empty; the warm start is not a cold one, so the
// chain's "cold" step applies); if none converges, `available` is false and
// the numbers are those of its last iterate.
ErrorEstimate estimateError(const HbModel& model, const Eigen::VectorXd& full, Solver& solver,
                            const SolverOptions& options, bool condensed,
                            const FallbackChain* fallbacks = nullptr);

// The same comparison when the solution on twice the harmonics is already known.
ErrorEstimate compareWithRefined(const HbModel& model, const Eigen::VectorXd& full, const HbModel& refined_model,
                                 const Eigen::VectorXd& refined_full);

}  // namespace eqhb
