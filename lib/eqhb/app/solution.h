// The result of app::solve: one harmonic-balance solve of a scene with how
// it started, what it fell back on, its times, and what was computed on the
// answer (stability, error estimate, accuracy target, refinement by
// shooting). Every writer (JSON, text, Python dicts) reads this one model.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/accuracy/accuracy_target.h"
#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/app/rho_candidates.h"
#include "eqhb/continuation/coarse_start.h"
#include "eqhb/continuation/fallback_chain.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/harmonic_balance/invariants.h"
#include "eqhb/orbits/orbit_refinement.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/solvers/solver.h"
#include "eqhb/stability/hill_stability.h"

namespace eqhb::app {

// One harmonic-balance solve (repeated) and what it used.
struct HbRun {
  Scene scene;                       // as solved: ω, H, N, ρ
  std::unique_ptr<HbSystem> system;
  SolverResult result;               // the last repeat's, or the fallback's
  SolverOptions options;             // as validated
  std::vector<double> times;         // per repeat, sorted; coarse start and fallbacks included
  double setup_seconds = 0.0;        // building the systems (patterns, factorisations)
  // How the solve started: "coarse" (cold_start used), "zero",
  // "from-harmonics" or "given".
  std::string start;
  ColdStartReport cold_start;        // the coarse start of the last repeat (used = false: none)
  FallbackReport fallback;           // the fallback steps after a failed solve (none tried: empty)
  std::vector<std::string> warnings; // things the caller should be told (a seed that did not converge)

  double medianSeconds() const;
  Eigen::VectorXd full() const { return system->fullCoefficients(result.solution); }
};

// The chosen discretisation of an accuracy target, with the ρ candidates.
struct AccuracyReport {
  double tolerance = 0.0;
  AccuracyChoice choice;
  RhoCandidates candidates;
  double rhoFactor() const { return candidates.factors[choice.candidate]; }
};

// How the linear algebra went.
struct LinearAlgebraReport {
  bool sparse_solver = false;    // the backend's Jacobians and factorisations
  bool condensation = false;     // a condensed system (A_k factored)
  bool sparse_factors = false;   // A_k by UMFPACK
  double factor_mib = 0.0;       // memory of the factors
  double peak_rss_mib = 0.0;     // of the process, after the solve
};

struct Solution {
  HbRun run;
  // The answer reported: the harmonic-balance solution, or the exact orbit's
  // truncation after a converged refinement (on `reported`'s H).
  HbModel reported;
  Eigen::VectorXd full;          // [x; λ] on reported.basis, FullSystem layout
  HbSolution summary;            // of `full` (max|x| the orbit's after a refinement)
  HbSolution plain;              // of the harmonic-balance solution
  LinearAlgebraReport linear_algebra;
  std::vector<LawInvariants> invariants;
  std::optional<HillResult> stability;          // asked and converged
  std::optional<ErrorEstimate> error_estimate;  // asked (or from the accuracy ladder) and converged
  std::optional<AccuracyReport> accuracy;       // asked
  std::optional<orbits::RefinedSolution> refinement;  // asked and converged
  double restitution = 0.0;                     // of the refinement

  const HbModel& model() const { return run.scene.model; }
  bool converged() const { return run.result.converged(); }
  // Converged, and the accuracy target and the refinement (when asked) met.
  bool succeeded() const;
};

}  // namespace eqhb::app
