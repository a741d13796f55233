// Failure maps: where each backend stops finding the periodic solution.
// Grids, per scene and backend (each a row of success/failure):
//   start      the converged solution z* perturbed by σ·rms(z*)·ξ (ξ standard
//              normal, 5 seeds per σ), and the cold start z = 0 (σ = "cold")
//   harmonics  H from 5 to 80, cold start
//   rho        the law scaling ρ from 0.01 to 100, cold start
//   forcing    the loads scaled by 0.25 .. 4, cold start
// on the condensed system, or the full one where the own dogleg cannot
// solve the condensed one from a cold start (contact).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace eqhb::bench {

struct FailureRow {
  std::string scene, grid, solver, value;
  int seed = 0;
  bool converged = false;
  std::string termination;
  int iterations = 0;
  double seconds = 0.0;
};

std::vector<FailureRow> failureMaps(const std::filesystem::path& scene, const std::vector<std::string>& solvers,
                                    bool quick);

}  // namespace eqhb::bench
