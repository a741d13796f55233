// `eqhb solve`: one harmonic-balance solve of a scene, reported as text or JSON.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/continuation/coarse_start.h"
#include "eqhb/continuation/fallback_chain.h"
#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/solvers/solver.h"
#include "eqhb/stability/hill_stability.h"
#include "accuracy_options.h"
#include "refine_options.h"
#include "scene_arguments.h"

namespace eqhb::cli {

struct SolveArguments {
  SceneArguments scene;
  std::string solver = "dogleg";
  bool full = false;
  bool json = false;
  bool trajectory = false;
  std::vector<std::string> backend_options;   // --option
  double tolerance = 1e-10;
  int max_iterations = 1000;
  int max_evaluations = 10000;
  double time_limit = 0.0;
  int repeat = 1;
  std::optional<int> from_harmonics;  // seed by continuation in H from this H₀
  std::string cold_start = "coarse";  // --cold-start: coarse (CoarseStart) or zero
  std::string linear_algebra = "auto";  // --linear-algebra: auto, dense or sparse
  std::string fallback = "default";     // --fallback: steps after a failed solve (default_path.h)
  bool stability = false;  // --stability: Floquet multipliers by Hill's method
  AccuracyArguments accuracy;           // --error-estimate, --accuracy (solve only)
  RefineArguments refine;               // --refine shoot (solve only)
  Eigen::VectorXd start_full;           // initial guess, FullSystem layout (empty: zero)
};

// One harmonic-balance solve (repeated --repeat times) and what it used.
struct HbRun {
  Scene scene;
  std::unique_ptr<HbSystem> system;
  SolverResult result;
  SolverOptions options;
  std::vector<double> times;  // sorted
  double setup_seconds = 0.0;  // building the system (pattern, factorisations)
  ColdStartReport cold_start;  // the coarse start of the last repeat (used = false: none)
  FallbackReport fallback;     // the fallback steps after a failed solve (none tried: empty)
};
HbRun solveHarmonicBalance(const SolveArguments& args);
// The common solver options and the --option pass-through; throws InputError.
SolverOptions solverOptions(const SolveArguments& args);

// One channel's Fourier coefficients as {"harmonics", "cos", "sin"}.
nlohmann::json coefficientsJson(const HarmonicSet& basis, const Eigen::VectorXd& coefficients);
// The coarse start of a cold solve as JSON (harmonics, samples, its solve,
// whether the fine solve was retried from zero); without one, only the kind
// of start, `otherwise` ("zero", "from-harmonics", "given").
nlohmann::json coldStartJson(const ColdStartReport& report, const std::string& otherwise);
// Every DOF and law component of a solution [x; λ]: "dofs" and "laws" arrays
// with coefficients and the largest magnitude over one period.
nlohmann::json solutionJson(const HbModel& model, const HbSolution& solution);

void addSolveCommand(CLI::App& app, SolveArguments& args);
// The --stability flag (solve and sweep).
void addStabilityFlag(CLI::App* command, SolveArguments& args);
// A Hill analysis as JSON: stable, spectral_radius, multipliers and
// exponents ([re, im], largest |multiplier| first), counts and time.
nlohmann::json stabilityJson(const HillResult& hill);
// Solver options and the backend's pass-through options from the flags;
// throws InputError.
void addSolverOptions(CLI::App* command, SolveArguments& args);
// Returns the process exit code: 0 converged, 1 not converged.
int runSolve(const SolveArguments& args);

}  // namespace eqhb::cli
