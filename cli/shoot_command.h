// `eqhb shoot`: the exact periodic orbit of a scene by shooting from a
// harmonic-balance solution, its Floquet multipliers and events.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>

#include "solve_command.h"

namespace eqhb::cli {

struct ShootArguments {
  SolveArguments hb;                 // scene, and the harmonic-balance start
  std::optional<int> from_hb;        // H of the start (default: the scene's)
  double restitution = 0.0;          // Newton impact coefficient e
  double tolerance = 1e-11;          // relative period residual
  int max_iterations = 40;
};

void addShootCommand(CLI::App& app, ShootArguments& args);
// Exit code: 0 converged, 1 not converged.
int runShoot(const ShootArguments& args);

}  // namespace eqhb::cli
