// `eqhb solve`: one harmonic-balance solve of a scene (app::solve), reported
// as text or JSON. The flags shared with the other commands that solve
// (sweep, study, shoot, compare) are read here too.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eqhb/app/solve.h"
#include "eqhb/output/solution_json.h"
#include "accuracy_options.h"
#include "refine_options.h"
#include "scene_arguments.h"

namespace eqhb::cli {

// The flags as given; defaults are app::SolveOptions'.
struct SolveArguments {
  SceneArguments scene;
  std::string solver = app::SolverChoice{}.solver;
  bool full = false;
  bool json = false;
  bool trajectory = false;
  std::vector<std::string> backend_options;   // --option NAME=VALUE
  double tolerance = SolverOptions{}.residual_tolerance;
  int max_iterations = SolverOptions{}.max_iterations;
  int max_evaluations = SolverOptions{}.max_evaluations;
  double time_limit = SolverOptions{}.time_limit;
  int repeat = app::SolveOptions().repeat;
  std::optional<int> from_harmonics;
  std::string cold_start = app::SolveOptions().cold_start;  // coarse or zero
  std::string linear_algebra = "auto";                      // auto, dense or sparse
  std::string fallback = app::SolverChoice{}.fallback;
  bool stability = false;
  std::string stability_method = "auto";
  double stability_time_limit = app::SolutionChecks{}.stability_time_limit;  // seconds, 0: none
  AccuracyArguments accuracy;  // --error-estimate, --accuracy (solve only)
  RefineArguments refine;      // --refine shoot (solve only)
};

// The application layer's options from the flags; throws InputError.
app::SolveOptions solveOptions(const SolveArguments& args);
// The common solver options and the --option pass-through; throws InputError.
SolverOptions solverOptions(const SolveArguments& args);
// The backend, system, limits (solverOptions) and --fallback, as every
// command that solves passes them on; throws InputError.
void readSolverChoice(const SolveArguments& args, app::SolverChoice* options);
// --stability, --stability-method, --error-estimate, --accuracy, --max-harmonics.
void readSolutionChecks(const SolveArguments& args, app::SolutionChecks* options);

void addSolveCommand(CLI::App& app, SolveArguments& args);
// The --stability flag (solve and sweep).
void addStabilityFlag(CLI::App* command, SolveArguments& args);
// Solver options and the backend's pass-through options.
void addSolverOptions(CLI::App* command, SolveArguments& args);
// The harmonic-balance solve alone (app::solveHarmonicBalance), its warnings
// on stderr.
app::HbRun solveHarmonicBalance(const SolveArguments& args);
// Returns the process exit code: 0 converged, 1 not converged.
int runSolve(const SolveArguments& args);

// The writers sweep reads a point with.
using output::stabilityJson;
inline nlohmann::json solutionJson(const HbModel& model, const HbSolution& solution) {
  return output::channelsJson(model, solution);
}

}  // namespace eqhb::cli
