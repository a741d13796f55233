// `eqhb shoot`: the exact periodic orbit of a scene by shooting from a
// harmonic-balance solution (app::shoot), its Floquet multipliers and events.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>

#include "eqhb/app/shoot.h"
#include "solve_command.h"

namespace eqhb::cli {

struct ShootArguments {
  SolveArguments hb;           // scene, and the harmonic-balance start
  std::optional<int> from_hb;  // H of the start (default: the scene's)
  double restitution = app::ShootOptions{}.restitution;
  double tolerance = app::ShootOptions{}.tolerance;
  int max_iterations = app::ShootOptions{}.max_iterations;
};

void addShootCommand(CLI::App& app, ShootArguments& args);
// Exit code: 0 converged, 1 not converged.
int runShoot(const ShootArguments& args);

}  // namespace eqhb::cli
