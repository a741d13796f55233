// `eqhb solve`: one harmonic-balance solve of a scene, reported as text or JSON.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace eqhb::cli {

struct SolveArguments {
  std::string scene;
  std::optional<double> omega, rho;
  std::optional<int> harmonics, samples;
  std::optional<std::string> form;
  std::string solver = "dogleg";
  bool full = false;
  bool json = false;
  bool trajectory = false;
  std::vector<std::string> overrides;         // --set
  std::vector<std::string> backend_options;   // --option
  double tolerance = 1e-10;
  int max_iterations = 1000;
  int max_evaluations = 10000;
  double time_limit = 0.0;
  int repeat = 1;
};

void addSolveCommand(CLI::App& app, SolveArguments& args);
// Returns the process exit code: 0 converged, 1 not converged.
int runSolve(const SolveArguments& args);

}  // namespace eqhb::cli
