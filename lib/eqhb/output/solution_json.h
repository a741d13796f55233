// JSON writers of a harmonic-balance solution (app::Solution) and of its
// parts, which curves and studies reuse. Keys are those of `eqhb solve
// --json`; DOFs and laws are numbered from 1 and law components are labelled
// as HbSolution labels them ("law1.lambda", "law2.lambda1", ...).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/accuracy/accuracy_target.h"
#include "eqhb/accuracy/error_estimate.h"
#include "eqhb/app/solution.h"
#include "eqhb/continuation/coarse_start.h"
#include "eqhb/continuation/fallback_chain.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/invariants.h"
#include "eqhb/orbits/orbit_refinement.h"
#include "eqhb/stability/hill_stability.h"

namespace eqhb::output {

// The whole solve: settings, the solver's report, start, fallbacks, times,
// linear algebra, "dofs", "shown" (the names of the DOFs the outputs show,
// scenes/dof_choice.h) and "laws", invariants, and the optional parts
// (stability, rho and accuracy, error_estimate, refinement, trajectory).
nlohmann::json solutionJson(const app::Solution& solution, bool trajectory);

// One channel's Fourier coefficients as {"harmonics", "cos", "sin"}.
nlohmann::json coefficientsJson(const HarmonicSet& basis, const Eigen::VectorXd& coefficients);
// Every DOF and law component of a solution [x; λ]: "dofs" and "laws" arrays
// with coefficients and the largest magnitude over one period; each DOF
// and each DOF a law reads by number from 1 and name ("name", "dof_name":
// a beam's "w3", else "x3"; dofLabel, hb_solution.h).
nlohmann::json channelsJson(const HbModel& model, const HbSolution& solution);
// The coarse start of a cold solve (harmonics, samples, its solve, whether the
// fine solve was retried from zero); without one, only the kind of start,
// `otherwise` ("zero", "from-harmonics", "given").
nlohmann::json coldStartJson(const ColdStartReport& report, const std::string& otherwise);
// {"taken" (null when none converged), "attempts": [{step, solver, termination,
//  iterations, residual_norm, seconds}], "seconds"}
nlohmann::json fallbackJson(const FallbackReport& report);
// A Hill analysis: stable, spectral_radius, multipliers and exponents
// ([re, im], largest |multiplier| first), counts and time; "method" when
// not Hill's, "note" when another method answered than the one asked.
nlohmann::json stabilityJson(const HillResult& hill);
// [{"law", "type", "violations": {name: value}}]
nlohmann::json invariantsJson(const std::vector<LawInvariants>& invariants);
// {"max_abs", "coefficients", "max_abs_difference", "factor", "method",
//  "refined_harmonics", "refined_samples", "refined_converged"}
nlohmann::json errorEstimateJson(const ErrorEstimate& estimate);
// {"tolerance", "reached", "failure", "seconds", "ladder": [{harmonics, samples, converged, estimate, seconds}],
//  "rho_factor", "rho_candidates": [{"rho_factor", "ladder"}] (when chosen among several)}
nlohmann::json accuracyJson(const AccuracyChoice& choice, double tolerance, const std::vector<double>& factors = {1.0});
// The chosen ρ: one number when every law with ρ has the same, else one per
// law (null for a law without); "scene" when no law has ρ. A scale-free ρ
// reads {"rho_factor": f}.
nlohmann::json rhoJson(const std::vector<std::optional<RhoSetting>>& scene_rho, double factor);
// {"method", "converged", "failure", "period_residual", "iterations",
//  "flow_evaluations", "harmonics", "samples", "seconds", "restitution",
//  "hb_max_abs": [per DOF, plain harmonic balance], "max_abs": [per DOF, exact]}
nlohmann::json refinementJson(const orbits::RefinedSolution& refined, const HbSolution& plain, double restitution);
// One period on the model's N samples: "t", then every channel by its label.
nlohmann::json trajectoryJson(const HbModel& model, const HbSolution& solution, int samples);

}  // namespace eqhb::output
